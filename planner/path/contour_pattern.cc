// Contour-parallel fill: inward offset rings d2 apart (dissertation eq. 3.17), each ring one weld pass.
#include "planner/path/contour_pattern.h"

#include "planner/geometry/clipper_adapter.h"
#include "planner/path/pattern_common.h"

namespace waam::planner::internal {

void PlanContour(const PolygonWithHoles& region, const PatternOptions& options, const OverlapSpacing& spacing,
                 std::vector<Move2D>* moves) {
  const double fraction = StartFraction(options);
  const bool reverse = options.alternate_start && options.layer_index % 2 == 1;
  // Ring k has its centre line at w/2 + k d2 from the outline (round joins: the offset keeps its distance around
  // re-entrant corners). Stop when the offset vanishes: the last ring is then less than d2 from the medial axis.
  // The first ring starts at the layer's rotating start point; every further ring where the torch stopped.
  const std::size_t first_move = moves->size();
  auto start_near = [&](const Ring& ring) {
    return moves->size() == first_move ? PointAlongRing(ring, fraction) : moves->back().p;
  };
  for (int k = 0;; ++k) {
    const double inset = spacing.boundary_offset_mm + k * spacing.contour_to_contour_mm;
    const std::vector<PolygonWithHoles> rings = Offset({region}, -inset);
    if (rings.empty()) break;
    for (const PolygonWithHoles& ring_region : rings) {
      // Where the offset reaches the medial axis of a wall an exact number of rings wide, it leaves crumbs along it:
      // inner rings shorter than a bead width, each of which would be an arc start and stop on the spot laying a
      // blob on metal the ring before already covers (a 70 deg arc band two beads wide got 10-14 of them per
      // layer). The first ring is always laid: on an island about a bead wide, the spot is the whole path.
      if (k > 0 && Perimeter(ring_region.outer) < options.bead_width_mm) continue;
      AppendLoop(ring_region.outer, start_near(ring_region.outer), reverse, moves);
      for (const Ring& hole : ring_region.holes) AppendLoop(hole, start_near(hole), reverse, moves);
    }
  }
}

}  // namespace waam::planner::internal
