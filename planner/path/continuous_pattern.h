// Ding et al. 2014 continuous path: convex pieces, contour + zigzag loop per piece, linked into one pass.
#pragma once

#include <vector>

#include "planner/geometry/polygon.h"
#include "planner/path/layer_pattern.h"

namespace waam::planner::internal {

// Appends the moves of the continuous pattern for one region (mm) to `moves`; `spacing` from OverlapSpacingFor.
// Where the convex decomposition fails on degenerate geometry, the region is planned with the hybrid pattern and a
// line saying so is appended to `notes` (not null).
void PlanContinuous(const PolygonWithHoles& region, const PatternOptions& options, const OverlapSpacing& spacing,
                    std::vector<Move2D>* moves, std::vector<std::string>* notes);

}  // namespace waam::planner::internal
