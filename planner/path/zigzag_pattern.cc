// Zigzag fill: raster lines l = 0.738 w apart inside the region inset by w/2, linked where the link stays inside.
#include "planner/path/zigzag_pattern.h"

#include "planner/geometry/clipper_adapter.h"
#include "planner/path/pattern_common.h"

namespace waam::planner::internal {

void PlanZigzag(const PolygonWithHoles& region, const PatternOptions& options, const OverlapSpacing& spacing,
                std::vector<Move2D>* moves) {
  const double inset = spacing.boundary_offset_mm;
  const std::vector<PolygonWithHoles> area = Offset({region}, -inset);
  if (area.empty()) return;
  const std::vector<PolygonWithHoles> link_area = Offset({region}, -(inset - LinkSlackMm(options)));
  std::vector<Move2D> own;
  // Links longer than a few step-overs would run along the wall like a contour; those become travel moves.
  LinkRasters(RasterFill(area, RasterAngle(region, options), spacing.zigzag_mm), link_area, 3.0 * spacing.zigzag_mm,
              &own);
  // Odd layers run the zigzag backwards, so the arc starts of consecutive layers sit at opposite ends.
  if (options.alternate_start && options.layer_index % 2 == 1) own = ReverseMoves(own);
  moves->insert(moves->end(), own.begin(), own.end());
}

}  // namespace waam::planner::internal
