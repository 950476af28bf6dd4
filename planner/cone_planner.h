// Cone and cylinder planning (Dai et al. 2020): equidistant developable layers, filled flat and mapped back, the
// tool along the surface normal, CSW travel speed from the path curvature.
#pragma once

#include "planner/planar_planner.h"

namespace waam::planner {

// Plans a scenario with slicing.type cone or cylinder: slices the part with the equidistant surfaces of the
// scenario's first surface at (i + 1/2) d (d = slicing.layer_height_mm), flattens each layer, fills it with the
// scenario's planar pattern, maps the path back onto the layer's top surface at (i + 1) d and points the tool along
// the surface normal. The part stays in its own frame (the surface's axis is given in it; the part is not moved
// onto the substrate: the spindle or shaft the layers grow on is the substrate). Travel speed per point from the
// CSW model when process.bead_model = csw. Throws InputError for a part that cannot be sliced this way (past the
// apex, inside the first surface, a contour winding round the axis). `progress` may be null.
PlanResult PlanConeScenario(const PlannerSections& scenario, Progress* progress);

}  // namespace waam::planner
