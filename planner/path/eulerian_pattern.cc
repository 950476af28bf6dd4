// Eulerian path for double-bead rib-web walls (dissertation 003 sec. 4.3, Fig. 26-27): every wall is welded by two
// offset curves, and 2 (n - 1) connector lines join the n curves of a slice into ONE closed weld pass.
#include "planner/path/eulerian_pattern.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <random>

#include "models/core/error.h"
#include "planner/geometry/clipper_adapter.h"
#include "planner/path/pattern_common.h"

namespace waam::planner::internal {
namespace {

using Vec = Eigen::Vector2d;

// Two curve segments count as side by side when they are parallel within this angle (sin) ...
constexpr double kParallelSin = 0.087;  // 5 degrees
// ... and at least this far apart (mm): coincident curves are a degenerate offset, not two beads.
constexpr double kMinGapMm = 0.05;
// Largest ratio of a mitred turning point's distance from the outline to the offset distance (Clipper MiterLimit):
// 6 keeps corners down to 2 asin(1/6) = 19 degrees sharp, as the dissertation's turning points P are (Fig. 28).
constexpr double kMiterLimit = 6.0;

double Cross(const Vec& a, const Vec& b) { return a.x() * b.y() - a.y() * b.x(); }

// A stretch where segment `seg_a` of curve `a` and segment `seg_b` of curve `b` run side by side `gap` mm apart;
// [s0, s1] is the shared stretch in mm along seg_a from its first point.
struct SharedStretch {
  std::size_t a = 0, seg_a = 0, b = 0, seg_b = 0;
  double s0 = 0.0, s1 = 0.0, gap = 0.0;
};

// One pair of connector lines: the stretch [c - g/2, c + g/2] is cut out of both curves.
struct RibCut {
  SharedStretch where;
  Vec a_lo, a_hi, b_lo, b_hi;    // cut ends on curve a (in a's direction) and their projections on curve b
  double u_lo = 0.0, u_hi = 0.0;  // the same ends in mm along seg_b from its first point
  double c_lo = 0.0, c_hi = 0.0;  // in mm along seg_a
};

struct UnionFind {
  std::vector<std::size_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::size_t Find(std::size_t i) { return parent[i] == i ? i : parent[i] = Find(parent[i]); }
};

std::vector<SharedStretch> FindSharedStretches(const std::vector<Ring>& curves, double max_gap_mm) {
  std::vector<SharedStretch> out;
  for (std::size_t a = 0; a < curves.size(); ++a) {
    for (std::size_t b = a + 1; b < curves.size(); ++b) {
      const Ring& ra = curves[a];
      const Ring& rb = curves[b];
      for (std::size_t i = 0; i < ra.size(); ++i) {
        const Vec a0 = ra[i], a1 = ra[(i + 1) % ra.size()];
        const double len_a = (a1 - a0).norm();
        if (len_a < 1e-9) continue;
        const Vec da = (a1 - a0) / len_a;
        for (std::size_t j = 0; j < rb.size(); ++j) {
          const Vec b0 = rb[j], b1 = rb[(j + 1) % rb.size()];
          const double len_b = (b1 - b0).norm();
          if (len_b < 1e-9) continue;
          const Vec db = (b1 - b0) / len_b;
          if (std::abs(Cross(da, db)) > kParallelSin) continue;
          const double gap0 = std::abs(Cross(da, b0 - a0));
          const double gap1 = std::abs(Cross(da, b1 - a0));
          const double gap = 0.5 * (gap0 + gap1);
          if (gap < kMinGapMm || gap > max_gap_mm) continue;
          const double t0 = (b0 - a0).dot(da), t1 = (b1 - a0).dot(da);
          const double s0 = std::max(0.0, std::min(t0, t1));
          const double s1 = std::min(len_a, std::max(t0, t1));
          // Room for the cut (one gap long) in the middle third of the stretch.
          if (s1 - s0 < 3.0 * gap) continue;
          out.push_back({a, i, b, j, s0, s1, gap});
        }
      }
    }
  }
  return out;
}

bool Overlaps(const std::vector<std::pair<double, double>>& taken, double lo, double hi) {
  for (const auto& [t_lo, t_hi] : taken) {
    if (lo < t_hi && t_lo < hi) return true;
  }
  return false;
}

// A random spanning tree of the "side by side" graph of the curves (Kruskal over the shuffled `stretches`). A tree
// never joins two curves twice, which would split them into a closed sub-path again (003 Fig. 27e); the cut
// intervals on one segment never overlap (each stretch of wall is used once).
std::vector<RibCut> ChooseCuts(const std::vector<Ring>& curves, const std::vector<SharedStretch>& stretches,
                               const std::vector<PolygonWithHoles>& area, std::mt19937_64& rng) {
  UnionFind groups(curves.size());
  std::vector<std::vector<std::vector<std::pair<double, double>>>> taken(curves.size());
  for (std::size_t k = 0; k < curves.size(); ++k) taken[k].resize(curves[k].size());
  std::vector<RibCut> cuts;
  for (const SharedStretch& s : stretches) {
    if (groups.Find(s.a) == groups.Find(s.b)) continue;
    const Ring& ra = curves[s.a];
    const Ring& rb = curves[s.b];
    const Vec a0 = ra[s.seg_a], da = (ra[(s.seg_a + 1) % ra.size()] - a0).normalized();
    const Vec b0 = rb[s.seg_b], db = (rb[(s.seg_b + 1) % rb.size()] - b0).normalized();
    // Between one third and two thirds of the shared stretch, so connectors of successive layers do not stack up and
    // leave a trace on the wall. Sec. 4.3 says "of the selected segment"; we take the part of the segment the two
    // curves share, which is the whole segment for the straight walls of a grid and keeps the connectors on the wall
    // where the curves run side by side. The cut is one gap long, so the two connectors weld as much as they remove.
    const double third = (s.s1 - s.s0) / 3.0;
    const double c = std::uniform_real_distribution<double>(s.s0 + third, s.s0 + 2.0 * third)(rng);
    RibCut cut{s, {}, {}, {}, {}, 0.0, 0.0, c - 0.5 * s.gap, c + 0.5 * s.gap};
    cut.a_lo = a0 + cut.c_lo * da;
    cut.a_hi = a0 + cut.c_hi * da;
    cut.u_lo = (cut.a_lo - b0).dot(db);
    cut.u_hi = (cut.a_hi - b0).dot(db);
    cut.b_lo = b0 + cut.u_lo * db;
    cut.b_hi = b0 + cut.u_hi * db;
    const double u_min = std::min(cut.u_lo, cut.u_hi), u_max = std::max(cut.u_lo, cut.u_hi);
    const double margin = s.gap;  // keep cuts on one segment at least a gap apart
    if (Overlaps(taken[s.a][s.seg_a], cut.c_lo - margin, cut.c_hi + margin)) continue;
    if (Overlaps(taken[s.b][s.seg_b], u_min - margin, u_max + margin)) continue;
    if (!SegmentInside(cut.a_lo, cut.b_lo, area) || !SegmentInside(cut.a_hi, cut.b_hi, area)) continue;
    taken[s.a][s.seg_a].push_back({cut.c_lo, cut.c_hi});
    taken[s.b][s.seg_b].push_back({u_min, u_max});
    groups.parent[groups.Find(s.a)] = groups.Find(s.b);
    cuts.push_back(cut);
  }
  return cuts;
}

// +1 or -1 per curve, so that the two curves of every cut run in opposite directions along it: then the connectors
// go straight across the wall and do not cross (a tree can always be oriented so, root first). `cuts_of[r]`: the
// cuts on curve r.
std::vector<int> OrientCurves(std::size_t n_curves, const std::vector<RibCut>& cuts,
                              const std::vector<std::vector<std::size_t>>& cuts_of) {
  std::vector<int> orient(n_curves, 0);
  for (std::size_t root = 0; root < n_curves; ++root) {
    if (orient[root] != 0) continue;
    orient[root] = 1;
    std::queue<std::size_t> todo;
    todo.push(root);
    while (!todo.empty()) {
      const std::size_t r = todo.front();
      todo.pop();
      for (std::size_t k : cuts_of[r]) {
        const RibCut& cut = cuts[k];
        const std::size_t other = cut.where.a == r ? cut.where.b : cut.where.a;
        if (orient[other] != 0) continue;
        const bool same_direction = (cut.u_hi > cut.u_lo);  // b's segment runs the same way as a's
        orient[other] = same_direction ? -orient[r] : orient[r];
        todo.push(other);
      }
    }
  }
  return orient;
}

// Nodes: every curve vertex and cut end, in curve order; succ[] walks each oriented curve. node_*[k]: the nodes of
// cut k's ends on curve a (lo, hi) and on curve b.
struct CurveGraph {
  std::vector<Vec> pos;
  std::vector<std::size_t> succ;
  std::vector<std::size_t> a_lo, a_hi, b_lo, b_hi;
};

CurveGraph BuildCurveGraph(const std::vector<Ring>& curves, const std::vector<RibCut>& cuts,
                           const std::vector<std::vector<std::size_t>>& cuts_of, const std::vector<int>& orient) {
  CurveGraph g;
  g.a_lo.resize(cuts.size());
  g.a_hi.resize(cuts.size());
  g.b_lo.resize(cuts.size());
  g.b_hi.resize(cuts.size());
  for (std::size_t r = 0; r < curves.size(); ++r) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < curves[r].size(); ++i) {
      order.push_back(g.pos.size());
      g.pos.push_back(curves[r][i]);
      // RibCut ends on this segment, sorted along it.
      std::vector<std::pair<double, std::size_t*>> ends;
      for (std::size_t k : cuts_of[r]) {
        const RibCut& cut = cuts[k];
        if (cut.where.a == r && cut.where.seg_a == i) {
          ends.push_back({cut.c_lo, &g.a_lo[k]});
          ends.push_back({cut.c_hi, &g.a_hi[k]});
        }
        if (cut.where.b == r && cut.where.seg_b == i) {
          ends.push_back({cut.u_lo, &g.b_lo[k]});
          ends.push_back({cut.u_hi, &g.b_hi[k]});
        }
      }
      std::sort(ends.begin(), ends.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      const Vec p0 = curves[r][i];
      const Vec d = (curves[r][(i + 1) % curves[r].size()] - p0).normalized();
      for (auto& [s, node] : ends) {
        *node = g.pos.size();
        order.push_back(g.pos.size());
        g.pos.push_back(p0 + s * d);
      }
    }
    if (orient[r] < 0) std::reverse(order.begin(), order.end());
    g.succ.resize(g.pos.size());
    for (std::size_t k = 0; k < order.size(); ++k) g.succ[order[k]] = order[(k + 1) % order.size()];
  }
  return g;
}

}  // namespace

JoinedCurves JoinOffsetCurves(const std::vector<Ring>& curves, const std::vector<PolygonWithHoles>& area,
                              double max_gap_mm, std::uint64_t seed) {
  JoinedCurves result;
  result.curves = curves.size();
  if (curves.empty()) return result;
  std::mt19937_64 rng(seed);
  std::vector<SharedStretch> stretches = FindSharedStretches(curves, max_gap_mm);
  std::shuffle(stretches.begin(), stretches.end(), rng);
  const std::vector<RibCut> cuts = ChooseCuts(curves, stretches, area, rng);
  std::vector<std::vector<std::size_t>> cuts_of(curves.size());
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    cuts_of[cuts[k].where.a].push_back(k);
    cuts_of[cuts[k].where.b].push_back(k);
  }
  CurveGraph g = BuildCurveGraph(curves, cuts, cuts_of, OrientCurves(curves.size(), cuts, cuts_of));
  std::vector<std::size_t>& succ = g.succ;
  // Each cut removes the gap X-Y from curve a and the facing gap from curve b and crosses over: X -> partner(X)
  // along b, around b, then partner(Y) -> Y back onto a (a 2-opt move that merges two loops into one).
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const bool lo_first = succ[g.a_lo[k]] == g.a_hi[k];
    const std::size_t x = lo_first ? g.a_lo[k] : g.a_hi[k];
    const std::size_t y = lo_first ? g.a_hi[k] : g.a_lo[k];
    const std::size_t bx = lo_first ? g.b_lo[k] : g.b_hi[k];
    const std::size_t by = lo_first ? g.b_hi[k] : g.b_lo[k];
    succ[x] = bx;
    succ[by] = y;
  }
  // Walk the loops.
  const std::vector<Vec>& pos = g.pos;
  std::vector<bool> seen(pos.size(), false);
  for (std::size_t start = 0; start < pos.size(); ++start) {
    if (seen[start]) continue;
    Ring loop;
    for (std::size_t n = start; !seen[n]; n = succ[n]) {
      seen[n] = true;
      if (loop.empty() || (pos[n] - loop.back()).norm() > 1e-9) loop.push_back(pos[n]);
    }
    if (loop.size() > 1 && (loop.front() - loop.back()).norm() <= 1e-9) loop.pop_back();
    if (loop.size() >= 3) result.loops.push_back(std::move(loop));
  }
  result.connectors = 2 * cuts.size();
  return result;
}

std::vector<Ring> SharpOffsetCurves(const PolygonWithHoles& region, const OverlapSpacing& spacing) {
  std::vector<Ring> curves;
  for (int k = 0;; ++k) {
    const double inset = spacing.boundary_offset_mm + k * spacing.contour_to_contour_mm;
    ClipperLib::ClipperOffset offset(kMiterLimit, kArcToleranceMm * kClipperUnitsPerMm);
    offset.AddPaths(ToPaths(region), ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
    ClipperLib::PolyTree tree;
    offset.Execute(tree, -inset * kClipperUnitsPerMm);
    const std::vector<PolygonWithHoles> rings = FromPolyTree(tree);
    if (rings.empty()) break;
    for (const PolygonWithHoles& r : rings) {
      curves.push_back(r.outer);
      for (const Ring& hole : r.holes) curves.push_back(hole);
    }
  }
  return curves;
}

void PlanEulerian(const PolygonWithHoles& region, const PatternOptions& options, const OverlapSpacing& spacing,
                  std::vector<Move2D>* moves) {
  const std::vector<Ring> curves = SharpOffsetCurves(region, spacing);
  if (curves.empty()) return;
  // Neighbouring curves of one wall lie d2 apart; curves at most a bead width apart share a wall (their beads
  // overlap or touch), so a connector between them is welded on metal.
  const std::uint64_t seed = options.seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(options.layer_index);
  const JoinedCurves joined = JoinOffsetCurves(curves, {region}, options.bead_width_mm, seed);
  // A slice whose curves cannot all be joined is not a rib web of double-bead walls (e.g. a cell too small for a
  // straight stretch three gaps long, or walls that do not hold two beads side by side).
  WAAM_THROW_UNLESS(joined.loops.size() == 1,
                    "path.pattern eulerian: layer " << options.layer_index << ": the " << joined.curves
                        << " offset curves of the region near (" << region.outer.front().x() << ", "
                        << region.outer.front().y() << ") mm join into " << joined.loops.size()
                        << " closed passes, not 1: every wall must hold two beads at most one bead width ("
                        << options.bead_width_mm << " mm) apart along a straight stretch at least three gaps long");
  const double fraction = StartFraction(options);
  const bool reverse = options.alternate_start && options.layer_index % 2 == 1;
  const std::size_t first_move = moves->size();
  for (const Ring& loop : joined.loops) {
    const Vec start = moves->size() == first_move ? PointAlongRing(loop, fraction) : moves->back().p;
    AppendLoop(loop, start, reverse, moves);
  }
}

}  // namespace waam::planner::internal
