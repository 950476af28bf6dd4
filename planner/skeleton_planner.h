// Planning of bent thin-walled tubes with non-uniform layers (dissertation seed 003, sec. 6.3): skeleton slicing,
// per-point travel speed and bead width from the fitted speed-height and width-height models, inner and outer walls,
// and a continuous spiral or a per-layer (discontinuous) single-bead path.
#pragma once

#include <string>

#include "models/bead/speed_height_model.h"
#include "models/bead/width_height_model.h"
#include "planner/planar_planner.h"
#include "planner/slicing/skeleton_slicer.h"

namespace waam::planner {

struct SkeletonPathOptions {
  double point_spacing_mm = 2.0;  // > 0: distance between path points along a layer, mm (sec. 6.3.3: 2 mm)
  bool spiral = true;             // true: one weld pass climbing from layer to layer; false: one closed pass per layer
};

// Turns the slicing into a path: per point the layer thickness h (distance to the plane below), the travel speed
// v = f(h) (eq. 6.6, clamped to the feasible window) and the bead width w = f(h) (eq. 6.7); the torch along the layer
// normal. Each LayerPath's `slice` holds the layer's inner and outer wall (the mid curve shifted by -+ w/2, Fig. 64)
// in its plane's coordinates. The spiral has one LayerPath per loop: the first rises from the substrate, each next
// one blends layer i-1 into layer i, and the last closes the top (layers + 1 loops). Throws InputError for a
// non-positive spacing.
Plan BuildSkeletonPlan(const SkeletonSlicing& slicing, const models::SpeedHeightModel& speed_height,
                       const models::WidthHeightModel& width_height, const SkeletonPathOptions& options,
                       const std::string& name);

// Design rule eq. 6.4 (R_min >= 1.5 d for heights of 1-2 mm; in general R_min = d/2 (lambda + 1)/(lambda - 1) with
// lambda = h_max / h_min): throws InputError prefixed by `where` with the numbers when `bend_radius_mm` is smaller.
void CheckBendRule(double bend_radius_mm, double extent_mm, double h_min_mm, double h_max_mm, const std::string& where);

// The `slicing.type: skeleton` branch of PlanScenario: loads or generates the part (for a `bent_tube` generator the
// eq. 6.4 rule is checked on its parameters before slicing; for a mesh on the bend measured along the centroid chain),
// slices it along its skeleton and plans the path with `path.pattern` spiral or contour. Throws InputError.
PlanResult PlanSkeletonScenario(const PlannerSections& scenario, Progress* progress);

}  // namespace waam::planner
