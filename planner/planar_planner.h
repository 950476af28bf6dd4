// The planar planning pipeline: scenario -> mesh -> slices -> one path per layer -> statistics; the plan's result type.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/mesh/triangle_mesh.h"
#include "planner/path/layer_pattern.h"
#include "planner/path/retract.h"
#include "planner/path/tool_path.h"
#include "planner/path/void_filling.h"
#include "planner/scenario/scenario.h"
#include "planner/timeline/timeline.h"

namespace waam {
class Progress;
}

namespace waam::planner {

// One sub-volume of a multi-directional plan (planner/multidir_planner.h).
struct SubVolumeReport {
  std::string name;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // build direction, part frame (unit)
  int first_layer = 0;             // index of its first layer in the plan
  int layers = 0;
  double volume_mm3 = 0.0;         // sum of slice area x layer height
  double support_mm3 = 0.0;        // metal needed under overhangs to build it along its direction (Lim & Soh Table 1)
  std::vector<std::array<double, 4>> keep;  // its half-spaces n . p <= c (n, c mm): the split planes
  double centroid_lean_deg = 0.0;  // split: centroid_shift features: largest lean of the centroid chain (eq. 5.26), deg
  double unwelded_mm3 = 0.0;        // metal in slices where the path pattern gave no path (part of volume_mm3)
};

// Everything `waam plan` produces in memory; the analysis module writes it to plan.json, plan.h5 and PNGs.
struct PlanResult {
  TriangleMesh mesh;       // the part, welded, in the part frame (mm); the substrate top is z = 0
  std::vector<std::string> warnings;  // what was planned otherwise than asked, one line each ("layer 3: ...")
  MeshReport mesh_report;
  Plan plan;
  PathStats stats;
  double layer_height_mm = 0.0;     // slicing step actually used (part height / layer count)
  double bead_area_mm2 = 0.0;       // bead cross-section from the wire-feed volume balance (003 eq. 3.4)
  double bead_height_mm = 0.0;      // parabolic cap height of that area at the planned width (eq. 3.3)
  double layer_growth_mm = 0.0;     // height a layer of beads at the zigzag spacing l grows: area / l
  double travel_speed_mm_min = 0.0; // the welding speed used
  double bead_width_mm = 0.0;       // the bead width used (from the scenario or the width-height model)
  double contour_tolerance_mm = 0.0; // slices simplified to this before the patterns (w/100); 0: not simplified
  std::string speed_clamp = "none"; // speed_height mode: none | at_minimum | at_maximum of the feasible window
  std::vector<SubVolumeReport> sub_volumes;  // multi_directional only
  // Non-uniform layers (slicing.type skeleton): ranges over all weld points; equal to the values above otherwise.
  double layer_height_min_mm = 0.0;  // thinnest planned layer thickness at a point, mm
  double layer_height_max_mm = 0.0;  // thickest, mm
  double speed_min_mm_min = 0.0;     // slowest weld travel speed, mm/min
  double speed_max_mm_min = 0.0;     // fastest, mm/min
  int layers_out_of_range = 0;       // skeleton layers whose thickness left [h_min, h_max] (Fig. 56 could not fix)
  std::vector<Eigen::Vector3d> axis_P;  // skeleton: central axis (chain of section centroids), part frame, mm
  std::vector<CornerCorrection> void_corrections;  // junction corners moved by path.void_filling (003 sec. 4.4)
  RetractReport retract;             // the arc-off travels rebuilt by path.retract_mm (planner/path/retract.h)
  Timeline timeline;                 // where the build's time goes; stats.estimated_time_s is its total_s
};

// The planar branch of PlanScenario (planner/plan_scenario.h): the part's mesh sliced at the scenario's layer height
// and every layer planned with the scenario's pattern, arc-off moves straight on the layer. Throws InputError for a
// mesh that cannot be sliced or settings that cannot be planned. `progress` may be null.
PlanResult PlanPlanarScenario(const PlannerSections& scenario, Progress* progress);

// The layer-pattern options of the scenario's `path` section for beads `bead_width_mm` wide (layer index 0), slices
// simplified to kContourToleranceFraction of the width; shared by the planar, cone and multi-directional planners.
PatternOptions PatternOptionsFor(const PlannerSections& scenario, double bead_width_mm);

// Sets `result`'s bead from the scenario's travel speed (mm/min) and bead width (mm) with the height from the
// wire-feed volume balance (003 eq. 3.4: area = efficiency * wire area * wire feed / travel speed; eq. 3.3:
// A = 2wh/3), and the layer growth A / l at the zigzag spacing l; shared by the planar and multi-directional planners.
void SetVolumeBalanceBead(const PlannerSections& scenario, PlanResult* result);

}  // namespace waam::planner
