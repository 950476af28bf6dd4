// Ding et al.'s "existing hybrid method": contour rings at w/2 plus a zigzag interior d1 inside them, each a pass.
#include "planner/path/hybrid_pattern.h"

#include "planner/geometry/clipper_adapter.h"
#include "planner/path/pattern_common.h"

namespace waam::planner::internal {

void PlanHybrid(const PolygonWithHoles& region, const PatternOptions& options, const OverlapSpacing& spacing,
                std::vector<Move2D>* moves) {
  const double fraction = StartFraction(options);
  const bool odd = options.alternate_start && options.layer_index % 2 == 1;
  // One contour ring per boundary (outline and every hole), each its own pass, centre line w/2 inside the wall.
  // The outline's ring starts at the layer's rotating start point, the others where the torch stopped.
  const std::vector<PolygonWithHoles> contour = Offset({region}, -spacing.boundary_offset_mm);
  for (const PolygonWithHoles& ring_region : contour) {
    const bool first = &ring_region == &contour.front();
    AppendLoop(ring_region.outer, first ? PointAlongRing(ring_region.outer, fraction) : moves->back().p, odd, moves);
    for (const Ring& hole : ring_region.holes) AppendLoop(hole, moves->back().p, odd, moves);
  }
  // Zigzag interior: raster ends d1 from the contour centre line (eq. 3.15), lines l apart; links stay inside it.
  const double inset = spacing.boundary_offset_mm + spacing.contour_to_zigzag_mm;
  const std::vector<PolygonWithHoles> area = Offset({region}, -inset);
  if (area.empty()) return;
  const std::vector<PolygonWithHoles> link_area = Offset({region}, -(inset - LinkSlackMm(options)));
  std::vector<Move2D> zigzag;
  LinkRasters(RasterFill(area, RasterAngle(region, options), spacing.zigzag_mm), link_area, 3.0 * spacing.zigzag_mm,
              &zigzag);
  if (odd) zigzag = ReverseMoves(zigzag);
  moves->insert(moves->end(), zigzag.begin(), zigzag.end());
}

}  // namespace waam::planner::internal
