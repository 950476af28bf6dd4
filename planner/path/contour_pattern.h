// Contour-parallel fill: rings from the boundary inward, d2 apart, each ring one pass.
#pragma once

#include <vector>

#include "planner/geometry/polygon.h"
#include "planner/path/layer_pattern.h"

namespace waam::planner::internal {

// Appends the moves of the contour pattern for one region (mm) to `moves`; `spacing` from OverlapSpacingFor.
void PlanContour(const PolygonWithHoles& region, const PatternOptions& options, const OverlapSpacing& spacing,
                 std::vector<Move2D>* moves);

}  // namespace waam::planner::internal
