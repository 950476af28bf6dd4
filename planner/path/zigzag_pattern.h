// Zigzag (raster) fill of a region inset by half a bead, raster lines l apart, linked where the link stays inside.
#pragma once

#include <vector>

#include "planner/geometry/polygon.h"
#include "planner/path/layer_pattern.h"

namespace waam::planner::internal {

// Appends the moves of the zigzag pattern for one region (mm) to `moves`; `spacing` from OverlapSpacingFor.
void PlanZigzag(const PolygonWithHoles& region, const PatternOptions& options, const OverlapSpacing& spacing,
                std::vector<Move2D>* moves);

}  // namespace waam::planner::internal
