// Ding et al. 2014 continuous path: convex pieces, contour + zigzag loop per piece, linked into one pass.
#pragma once

#include <vector>

#include "planner/geometry/polygon.h"
#include "planner/path/layer_pattern.h"

namespace waam::planner::internal {

// Appends the moves of the continuous pattern for one region (mm) to `moves`; `spacing` from OverlapSpacingFor.
void PlanContinuous(const PolygonWithHoles& region, const PatternOptions& options, const OverlapSpacing& spacing,
                    std::vector<Move2D>* moves);

}  // namespace waam::planner::internal
