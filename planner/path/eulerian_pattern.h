// Eulerian path for double-bead rib-web walls: offset curves joined into one closed weld pass (003 sec. 4.3).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "planner/geometry/polygon.h"
#include "planner/path/layer_pattern.h"

namespace waam::planner::internal {

// The offset curves of a region joined by connector lines.
struct JoinedCurves {
  std::vector<Ring> loops;       // one loop when every curve could be joined, else one per connected group
  std::size_t curves = 0;        // offset curves before joining (n)
  std::size_t connectors = 0;    // connector lines added: 2 (n - loops)
};

// Joins closed offset curves (mm, any orientation) into as few closed loops as possible: two curves that run side
// by side at most `max_gap_mm` apart (> 0) along a stretch at least three gaps long are cut there, one gap of each
// removed and the ends joined by two connector lines across the gap. Curve pairs to join are drawn in a spanning
// tree with a std::mt19937_64 seeded by `seed`, each cut at a random place between one third and two thirds of the
// shared stretch, never two cuts on the same stretch. Connectors outside `area` (the slice) are not used.
JoinedCurves JoinOffsetCurves(const std::vector<Ring>& curves, const std::vector<PolygonWithHoles>& area,
                              double max_gap_mm, std::uint64_t seed);

// Offset curves of `region` with sharp (mitred) turning points: rings w/2 + k d2 inside the outline, k = 0, 1, ...
std::vector<Ring> SharpOffsetCurves(const PolygonWithHoles& region, const OverlapSpacing& spacing);

// Appends the moves of the Eulerian pattern of one region (mm): its offset curves joined into one closed weld pass.
void PlanEulerian(const PolygonWithHoles& region, const PatternOptions& options, const OverlapSpacing& spacing,
                  std::vector<Move2D>* moves);

}  // namespace waam::planner::internal
