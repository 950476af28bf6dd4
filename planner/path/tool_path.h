// The planned tool path: points with tool direction, bead size, speed and arc on/off, grouped by layer.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/geometry/polygon.h"

namespace waam::planner {

// One point of the torch path in the part frame P.
// `weld` describes the move that ENDS at this point: true = arc on (a bead is laid from the previous point to this
// one), false = arc off (a travel move). The first point of a layer has weld = false, except in a continuous spiral
// (path.pattern spiral), where weld = true means the move from the previous layer's last point continues its pass.
struct PathPoint {
  Eigen::Vector3d p_P = Eigen::Vector3d::Zero();               // TCP position, mm
  Eigen::Vector3d tool_dir_P = Eigen::Vector3d::UnitZ();       // unit vector from the TCP up the torch axis
  double bead_width_mm = 0.0;                                  // planned bead width, mm
  double bead_height_mm = 0.0;                                 // planned bead (layer) height, mm
  double speed_mm_s = 0.0;                                     // travel speed of the move ending here, mm/s
  bool weld = false;
  // Positioner (tilt, rotation) at this point as a program made elsewhere gives them, rad; NaN = not given (the
  // cell motion solves them from the build direction). Not written to plan.h5 / plan.json.
  Eigen::Vector2d positioner_rad = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  // Seconds the torch waits at this point once it has arrived, before the next move: a program's own wait (G-code G4,
  // FANUC WAIT, RAPID WaitTime, KRL WAIT SEC, INFORM TIMER), s >= 0. The timeline counts it as a wait.
  double dwell_s = 0.0;
};

// The path of one layer.
struct LayerPath {
  int index = 0;                                  // 0 = first layer on the substrate
  double z_mm = 0.0;                              // slicing height (planar) or mean height (curved), mm
  Eigen::Vector3d build_dir_P = Eigen::Vector3d::UnitZ();  // slice normal: the direction the layer grows
  std::vector<PolygonWithHoles> slice;            // the region the layer fills, in the slice plane (2D, mm)
  // Where the slice plane lies in P: a slice point (x, y) is slice_origin_P + slice_axes_P (x, y) (orthonormal
  // columns; the part's XY for a horizontal planar layer). Cone and cylinder layers keep their slice in the
  // development plane, which no such map reaches: slice_in_plane is false for them.
  Eigen::Matrix<double, 3, 2> slice_axes_P = Eigen::Matrix<double, 3, 2>::Identity();
  Eigen::Vector3d slice_origin_P = Eigen::Vector3d::Zero();
  bool slice_in_plane = true;
  std::vector<PathPoint> points;
};

// Summary measures of a path, as Ding et al. Table 2 counts them.
struct PathStats {
  std::size_t layers = 0;
  std::size_t passes = 0;          // arc starts over the whole part
  std::vector<std::size_t> passes_per_layer;
  std::size_t path_elements = 0;   // straight weld-on segments
  std::vector<std::size_t> path_elements_per_layer;
  double weld_length_mm = 0.0;
  double travel_length_mm = 0.0;
  // The build's duration: the total of its timeline (planner/timeline/timeline.h), set where the timeline is built
  // (PlanScenario without the cell, analysis::AddCellTimeline with it); ComputeStats leaves it 0. s
  double estimated_time_s = 0.0;
};

// A whole planned part.
struct Plan {
  std::string name;
  std::vector<LayerPath> layers;
};

// Counts passes, path elements and lengths (estimated_time_s is left 0: the timeline gives it).
PathStats ComputeStats(const Plan& plan);

}  // namespace waam::planner
