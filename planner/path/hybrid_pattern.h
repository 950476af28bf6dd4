// Ding's existing hybrid baseline: one contour ring per boundary plus a zigzag interior, each a separate pass.
#pragma once

#include <vector>

#include "planner/geometry/polygon.h"
#include "planner/path/layer_pattern.h"

namespace waam::planner::internal {

// Appends the moves of the hybrid pattern for one region (mm) to `moves`; `spacing` from OverlapSpacingFor.
void PlanHybrid(const PolygonWithHoles& region, const PatternOptions& options, const OverlapSpacing& spacing,
                std::vector<Move2D>* moves);

}  // namespace waam::planner::internal
