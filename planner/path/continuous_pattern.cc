// Ding et al. 2014 continuous path: convex pieces (3.1), one contour + zigzag loop each (3.2), linked into one pass (3.3).
//
// Linking (3.3) differs from the paper in how the links are found: Ding stores the split lines of the decomposition
// and re-routes the two sub-paths at each of them. Here the pieces' loops are joined along a spanning tree of the
// lines the pieces share (split lines and the merging lines of holes alike, longest first): near the end of the
// shared line that lies on the outline (Ding puts the connections on the outline), a short piece of each loop is
// cut out and the two loops are crossed over with two parallel links, like a 2-opt move. Two closed loops become
// one closed loop, so after the tree is done each region is one weld pass. A link must keep w/2 from the wall (or,
// failing that anywhere along the line, stay inside the region); a line where neither holds is skipped, and if the
// tree cannot be completed the remaining loops are separate passes joined by arc-off travel.
#include "planner/path/continuous_pattern.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "planner/geometry/clipper_adapter.h"
#include "planner/geometry/convex_decomposition.h"
#include "planner/path/convex_fill.h"
#include "planner/path/hybrid_pattern.h"
#include "planner/path/pattern_common.h"

namespace waam::planner::internal {
namespace {

using Vec = Eigen::Vector2d;

// A closed loop whose edge k (from point k to k+1) was laid in piece `piece[k]` (-1: a link between pieces).
struct TaggedLoop {
  std::vector<Vec> p;
  std::vector<int> piece;
};

struct Cut {
  std::size_t edge = 0;
  Vec first, second;  // the cut-out stretch along the edge direction
};

// Nearest edge of `loop` laid in `piece` to point m, and the stretch of length <= gap around it to cut out.
bool FindCut(const TaggedLoop& loop, int piece, const Vec& m, double gap, Cut* cut) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < loop.p.size(); ++k) {
    if (loop.piece[k] != piece) continue;
    const Vec& a = loop.p[k];
    const Vec& b = loop.p[(k + 1) % loop.p.size()];
    const double len = (b - a).norm();
    if (len < 1e-6) continue;
    const Vec u = (b - a) / len;
    const double g = std::min(gap, 0.5 * len);
    const double t = std::clamp((m - a).dot(u), 0.5 * g, len - 0.5 * g);
    const double d = (a + t * u - m).norm();
    if (d < best) best = d, *cut = Cut{k, a + (t - 0.5 * g) * u, a + (t + 0.5 * g) * u};
  }
  return std::isfinite(best);
}

TaggedLoop Reversed(const TaggedLoop& loop) {
  TaggedLoop r;
  const std::size_t n = loop.p.size();
  for (std::size_t k = 0; k < n; ++k) {
    r.p.push_back(loop.p[n - 1 - k]);
    r.piece.push_back(loop.piece[(2 * n - 2 - k) % n]);  // edge (n-1-k) -> (n-2-k) was edge n-2-k forward
  }
  return r;
}

// Walks `loop` from the end of the cut around to its start: second, p[edge+1], ..., p[edge], first.
void AppendFrom(const TaggedLoop& loop, const Cut& cut, int piece, TaggedLoop* out) {
  const std::size_t n = loop.p.size();
  out->p.push_back(cut.second);
  out->piece.push_back(piece);
  for (std::size_t k = 1; k <= n; ++k) {
    const std::size_t i = (cut.edge + k) % n;
    out->p.push_back(loop.p[i]);
    out->piece.push_back(loop.piece[i]);
  }
  out->p.push_back(cut.first);
  out->piece.push_back(-1);  // first -> the other loop is a link
}

// Joins loops x and y across shared line `edge`; false if no link position is acceptable.
bool JoinLoops(const TaggedLoop& x, TaggedLoop y, const SharedEdge& edge, double w, double gap,
               const std::vector<PolygonWithHoles>& strict, const std::vector<PolygonWithHoles>& loose,
               TaggedLoop* joined) {
  const double len = (edge.b - edge.a).norm();
  const Vec u = (edge.b - edge.a) / len;
  const double near = std::min(w, 0.5 * len);
  for (const auto* area : {&strict, &loose}) {
    for (double s : {near, 0.5 * len, len - near}) {
      const Vec m = edge.a + s * u;
      Cut cx, cy;
      if (!FindCut(x, edge.piece_a, m, gap, &cx) || !FindCut(y, edge.piece_b, m, gap, &cy)) return false;
      // The two cut edges must run in opposite directions for the two links to be parallel, not crossed.
      TaggedLoop yy = y;
      if ((cx.second - cx.first).dot(cy.second - cy.first) > 0.0) {
        yy = Reversed(y);
        if (!FindCut(yy, edge.piece_b, m, gap, &cy)) return false;
      }
      if (!SegmentInside(cx.first, cy.second, *area) || !SegmentInside(cy.first, cx.second, *area)) continue;
      joined->p.clear();
      joined->piece.clear();
      AppendFrom(x, cx, edge.piece_a, joined);
      AppendFrom(yy, cy, edge.piece_b, joined);
      return true;
    }
  }
  return false;
}

int Find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// Drops points where the loop goes straight on, so each weld move is one path element.
Ring Simplify(const std::vector<Vec>& in) {
  Ring out;
  const std::size_t n = in.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec& a = in[(i + n - 1) % n];
    const Vec& b = in[i];
    const Vec& c = in[(i + 1) % n];
    const Vec e1 = b - a, e2 = c - b;
    const bool straight = std::abs(e1.x() * e2.y() - e1.y() * e2.x()) <= 1e-9 * (e1.norm() * e2.norm()) &&
                          e1.dot(e2) > 0.0;
    if (!straight && e1.norm() > 1e-9) out.push_back(b);
  }
  return out;
}

}  // namespace

void PlanContinuous(const PolygonWithHoles& region, const PatternOptions& options, const OverlapSpacing& spacing,
                    std::vector<Move2D>* moves) {
  std::vector<Ring> pieces;
  try {
    pieces = DecomposeConvex(region);
  } catch (const std::logic_error&) {
    // A decomposition that fails on degenerate geometry falls back to the hybrid baseline for this region.
    PlanHybrid(region, options, spacing, moves);
    return;
  }
  const double w = options.bead_width_mm;
  std::vector<TaggedLoop> loops(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const double angle = options.zigzag_auto ? MinimumWidthDirection(pieces[i], nullptr) : options.zigzag_angle_rad;
    loops[i].p = ConvexPieceLoop(pieces[i], angle, spacing);
    loops[i].piece.assign(loops[i].p.size(), static_cast<int>(i));
  }
  // Kruskal over the shared lines, longest first: every accepted line joins two loops into one.
  const std::vector<PolygonWithHoles> strict = Offset({region}, -(spacing.boundary_offset_mm - 0.01));
  const std::vector<PolygonWithHoles> loose = Offset({region}, -0.01);
  std::vector<int> parent(pieces.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<int> loop_of(pieces.size());  // root piece -> index into loops holding its merged loop
  std::iota(loop_of.begin(), loop_of.end(), 0);
  for (const SharedEdge& edge : FindSharedEdges(pieces, region)) {
    const int ra = Find(parent, edge.piece_a), rb = Find(parent, edge.piece_b);
    if (ra == rb || loops[loop_of[ra]].p.size() < 3 || loops[loop_of[rb]].p.size() < 3) continue;
    TaggedLoop joined;
    if (!JoinLoops(loops[loop_of[ra]], loops[loop_of[rb]], edge, w, spacing.zigzag_mm, strict, loose, &joined)) {
      continue;
    }
    loops[loop_of[ra]] = std::move(joined);
    loops[loop_of[rb]] = TaggedLoop{};
    parent[rb] = ra;
  }
  // Each remaining loop is one pass; the start rotates along the outline layer by layer and odd layers run the
  // loop the other way, so arc starts and the direction of travel do not stack up.
  const Vec start = PointAlongRing(region.outer, StartFraction(options));
  const bool reverse = options.alternate_start && options.layer_index % 2 == 1;
  for (const TaggedLoop& loop : loops) {
    if (loop.p.size() >= 3) AppendLoop(Simplify(loop.p), start, reverse, moves);
  }
}

}  // namespace waam::planner::internal
