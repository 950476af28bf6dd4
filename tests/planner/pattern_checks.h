// Checks on planned layer paths shared by the pattern tests: pass counts, welded polylines, coverage, staying inside.
#pragma once

#include <algorithm>
#include <vector>

#include "planner/geometry/clipper_adapter.h"
#include "planner/path/layer_pattern.h"

namespace waam::planner::testing {

// Arc starts: a weld move that follows an arc-off move (the first move is always arc-off).
inline int CountPasses(const std::vector<Move2D>& moves) {
  int passes = 0;
  for (std::size_t k = 0; k < moves.size(); ++k) {
    if (moves[k].weld && (k == 0 || !moves[k - 1].weld)) ++passes;
  }
  return passes;
}

inline int CountWeldMoves(const std::vector<Move2D>& moves) {
  int n = 0;
  for (const Move2D& m : moves) n += m.weld ? 1 : 0;
  return n;
}

// The welded polylines: each run of weld moves with the point it starts from.
inline std::vector<internal::Polyline> WeldLines(const std::vector<Move2D>& moves) {
  std::vector<internal::Polyline> lines;
  for (std::size_t k = 1; k < moves.size(); ++k) {
    if (!moves[k].weld) continue;
    if (!moves[k - 1].weld || lines.empty()) lines.push_back({moves[k - 1].p});
    lines.back().push_back(moves[k].p);
  }
  return lines;
}

// Fraction of `region` left uncovered by beads of width `bead_width_mm` laid along the weld moves.
inline double UncoveredFraction(const PolygonWithHoles& region, const std::vector<Move2D>& moves,
                                double bead_width_mm) {
  const auto beads = internal::BufferPolylines(WeldLines(moves), 0.5 * bead_width_mm);
  return Area(internal::Difference({region}, beads)) / Area(region);
}

// Largest length (mm) of one weld move outside `area` (Clipper's 0.1 um grid makes ~1e-5 mm of noise).
inline double WeldLengthOutside(const std::vector<Move2D>& moves, const std::vector<PolygonWithHoles>& area) {
  double outside = 0.0;
  for (std::size_t k = 1; k < moves.size(); ++k) {
    if (!moves[k].weld) continue;
    const double len = (moves[k].p - moves[k - 1].p).norm();
    double in = 0.0;
    for (const internal::Polyline& piece : internal::ClipPolylines({{moves[k - 1].p, moves[k].p}}, area)) {
      in += internal::Length(piece);
    }
    outside = std::max(outside, len - in);
  }
  return outside;
}

}  // namespace waam::planner::testing
