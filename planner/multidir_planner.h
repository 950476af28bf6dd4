// Multi-directional planar planning (Lim & Soh, seed 002): the part split by user-given planes into sub-volumes,
// each planar-sliced along its own build direction, the positioner turning each one upright.
#pragma once

#include "planner/planar_planner.h"

namespace waam::planner {

// Plans a scenario with slicing.type multi_directional: for each sub-volume in order, slices the part with planes
// normal to its direction at slicing.layer_height_mm (rounded so the layers fill its extent along the direction),
// keeps what lies inside its half-spaces, fills each slice with the scenario's pattern and welds on the layer's top
// with the tool along the direction. Reports each sub-volume's volume and the support it needs along its direction
// (PlanResult::sub_volumes). With slicing.split centroid_shift the sub-volumes come from DecomposeByCentroidShift
// (planner/slicing/centroid_decomposition.h) at the layer height instead. The part stays in its own frame. Throws
// InputError for a sub-volume with no metal or a bead model other than volume_balance. `progress` may be null.
PlanResult PlanMultiDirectionalScenario(const PlannerSections& scenario, Progress* progress);

}  // namespace waam::planner
