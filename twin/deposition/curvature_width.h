// Bead width on curved paths: the curvature term of Dai et al.'s CSW model applied along an executed pass.
#pragma once

#include "models/bead/csw_model.h"
#include "twin/deposition/executed_path.h"

namespace waam::twin {

// Radius (mm) of the circle through the pass points at arc lengths s - window, s and s + window (clamped to the
// pass); +inf where they are collinear. `window_mm` > 0.
double PathRadiusAt(const ExecutedPass& pass, double s_mm, double window_mm);

// Sets each point's width_factor from the CSW model (Dai et al. 2020 sec. 4, w = m v^(-1/3) + p/r + t): the ratio of
// the width on the local radius r to the straight-line width at the same speed. The wire feed and speed set the
// bead's area, so SectionAt lowers the bead by the same factor. r is measured over one bead width each side of the
// move (PathRadiusAt). Two limits, so the model is not used outside what it describes:
// - r below one bead width is a corner, not a curve: the swept bead already piles metal on the inside of the turn,
//   so no widening is added there;
// - r is clamped up to `min_radius_mm`, the smallest radius of the beads the model was fitted to (30 mm in Dai's
//   Table 1): p/r grows without bound below it.
// Speeds are clamped to the model's feasible window.
void ApplyCurvatureWidth(const models::CswModel& csw, double min_radius_mm, ExecutedPass* pass);

}  // namespace waam::twin
