// Ding et al. 2014 continuous path: convex pieces (3.1), a contour + zigzag loop each (3.2), one pass (3.3).
//
// Linking (3.3) differs from the paper in how the links are found: Ding stores the split lines of the decomposition
// and re-routes the two sub-paths at each of them. Here the pieces' loops are joined along a spanning tree of the
// lines the pieces share (split lines and the merging lines of holes alike, longest first): near the end of the
// shared line that lies on the outline (Ding puts the connections on the outline), a short piece of each loop is
// cut out and the two loops are crossed over with two parallel links, like a 2-opt move. Two closed loops become
// one closed loop, so after the tree is done each region is one weld pass. A link must keep w/2 from the wall (or,
// failing that anywhere along the line, stay inside the region); a line where neither holds is skipped, and if the
// tree cannot be completed the remaining loops are separate passes joined by arc-off travel.
//
// Spacing along shared lines (not in the paper): Ding lays each piece's contour as if every side were a wall (3.2,
// Fig. 7). Two neighbouring pieces then put two beads w apart along their shared line, with nothing between them,
// and each rasters d1 (the free-wall gap) from its own contour: a valley along every split line that stacks up
// layer on layer (the twin's height maps of ding_a-c). Here a shared side gets its contour l/2 inside and the rasters
// l from it, so the beads across the line are spaced like all others (003 eq. 3.15). On the three-layer Ding
// scenarios this took Ra of the continuous path from 0.610 / 0.788 / 0.876 / 0.351 mm to 0.588 / 0.763 / 0.866 /
// 0.332 mm (ding_a-d) and W_t down on all four.
//
// Curved outlines (not in the paper): Ding decomposes the tessellated slice as it is, so every facet of a curved
// side is a notch, and a curved wall is cut into slivers narrower than a bead that get no path (a 70 deg arc band
// two beads wide, or the thruster's blade sections: 29 pieces from 68 vertices and not one weld move). The
// region decomposed here has its notches shallower than w/10 (kCurveToleranceFraction) cut off by chords
// (FillShallowNotches; convex sides are kept as they are), so a concave curve is cut a few times, not at every
// facet; the pieces' paths then lie at most w/10 further out than the true concave side (0.9 mm for 9 mm beads,
// about the height of the bead ripple): a little excess metal there instead of slivers with no path.
//
// Odd layers (not in the paper): each piece's loop is laid the other way round (BetterCoveringLoop), so the
// turnarounds and the contour change sides and their piles and gaps do not stack: 0.588 / 0.763 / 0.866 / 0.332 ->
// 0.561 / 0.717 / 0.848 / 0.343 mm.
#include "planner/path/continuous_pattern.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "planner/geometry/clipper_adapter.h"
#include "planner/geometry/convex_decomposition.h"
#include "planner/path/convex_fill.h"
#include "planner/path/hybrid_pattern.h"
#include "planner/path/pattern_common.h"

namespace waam::planner::internal {
namespace {

using Vec = Eigen::Vector2d;

// Depth of the notches that are cut off before the decomposition, in bead widths (see the file comment).
constexpr double kCurveToleranceFraction = 0.1;
// A hole with more vertices than this is treated as round (a bore): see SeparateRoundHoles.
constexpr int kRoundHoleVertices = 8;
// Sides of the coarse polygon that replaces a round hole in the decomposition.
constexpr int kRoundHoleSides = 8;

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

// A place to join two loops: near point m, cutting an edge of loop x laid in tag_x and one of loop y in tag_y.
struct JoinSite {
  Vec m = Vec::Zero();
  int tag_x = 0;
  int tag_y = 0;
};

// Joins loops x and y at the first site whose two links keep w/2 from the wall (strict) or, failing every site,
// stay inside the region (loose); false if none does.
bool JoinLoops(const TaggedLoop& x, const TaggedLoop& y, const std::vector<JoinSite>& sites, double gap,
               const std::vector<PolygonWithHoles>& strict, const std::vector<PolygonWithHoles>& loose,
               TaggedLoop* joined) {
  for (const auto* area : {&strict, &loose}) {
    for (const JoinSite& site : sites) {
      Cut cx, cy;
      if (!FindCut(x, site.tag_x, site.m, gap, &cx) || !FindCut(y, site.tag_y, site.m, gap, &cy)) continue;
      // The two cut edges must run in opposite directions for the two links to be parallel, not crossed.
      const bool flip = (cx.second - cx.first).dot(cy.second - cy.first) > 0.0;
      const TaggedLoop yy = flip ? Reversed(y) : y;
      if (flip && !FindCut(yy, site.tag_y, site.m, gap, &cy)) continue;
      if (!SegmentInside(cx.first, cy.second, *area) || !SegmentInside(cy.first, cx.second, *area)) continue;
      joined->p.clear();
      joined->piece.clear();
      AppendFrom(x, cx, site.tag_x, joined);
      AppendFrom(yy, cy, site.tag_y, joined);
      return true;
    }
  }
  return false;
}

// Ding 3.3: join across a shared line near its end on the outline (one link width in), else mid-line, else the
// other end.
std::vector<JoinSite> SharedEdgeSites(const SharedEdge& edge, double w) {
  const double len = (edge.b - edge.a).norm();
  const Vec u = (edge.b - edge.a) / len;
  const double near = std::min(w, 0.5 * len);
  std::vector<JoinSite> sites;
  for (double s : {near, 0.5 * len, len - near}) sites.push_back(JoinSite{edge.a + s * u, edge.piece_a, edge.piece_b});
  return sites;
}

// Fallback for loops that share no line (a hole's ring, or pieces whose shared line had no room for links): the
// closest pairs of edges of x and y, at most `max_distance` apart, nearest first.
std::vector<JoinSite> NearestSites(const TaggedLoop& x, const TaggedLoop& y, double max_distance) {
  std::vector<std::pair<double, JoinSite>> found;
  for (std::size_t i = 0; i < x.p.size(); ++i) {
    if (x.piece[i] < 0) continue;
    const Vec mx = 0.5 * (x.p[i] + x.p[(i + 1) % x.p.size()]);
    double best = max_distance;
    JoinSite site;
    for (std::size_t j = 0; j < y.p.size(); ++j) {
      if (y.piece[j] < 0) continue;
      const Vec a = y.p[j], b = y.p[(j + 1) % y.p.size()];
      const double l2 = (b - a).squaredNorm();
      const Vec q = a + (l2 > 0.0 ? std::clamp((mx - a).dot(b - a) / l2, 0.0, 1.0) : 0.0) * (b - a);
      if ((q - mx).norm() < best) best = (q - mx).norm(), site = JoinSite{0.5 * (mx + q), x.piece[i], y.piece[j]};
    }
    if (best < max_distance) found.emplace_back(best, site);
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<JoinSite> sites;
  for (std::size_t k = 0; k < found.size() && k < 12; ++k) sites.push_back(found[k].second);
  return sites;
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

// Area (mm2) of `piece` that beads of width w laid along the closed loop leave uncovered.
double UncoveredArea(const Ring& piece, const std::vector<Vec>& loop, double w) {
  if (loop.size() < 2) return Area(PolygonWithHoles{piece, {}});
  Polyline closed(loop.begin(), loop.end());
  closed.push_back(loop.front());
  return Area(Difference({PolygonWithHoles{piece, {}}}, BufferPolylines({closed}, 0.5 * w)));
}

// The piece's contour + zigzag loop with the rasters at `angle_rad`, laid either way round: the contour on one
// chain and the raster turnarounds on the other (Ding 3.2). Where a chain runs at a small angle to the rasters,
// consecutive raster ends lie far apart along it and turnarounds leave wedges next to the wall that only a contour
// fills; so the way round that leaves less of the piece uncovered is kept.
//
// On odd layers (`mirror`) the other way round is laid instead, unless it leaves more than 1 % of the piece
// uncovered beyond the better one: the turnarounds and the contour then change sides layer by layer, so their
// piles and gaps do not stack (both ways are Ding's loop: which chain is the "left" one follows the zigzag's sense).
std::vector<Vec> BetterCoveringLoop(const Ring& piece, const std::vector<bool>& shared, double angle_rad, double w,
                                    const OverlapSpacing& spacing, bool mirror) {
  std::vector<Vec> best = ConvexPieceLoop(piece, angle_rad, spacing, shared);
  std::vector<Vec> other = ConvexPieceLoop(piece, angle_rad + std::numbers::pi, spacing, shared);
  double best_uncovered = UncoveredArea(piece, best, w), other_uncovered = UncoveredArea(piece, other, w);
  if (other_uncovered < best_uncovered - 1e-6) std::swap(best, other), std::swap(best_uncovered, other_uncovered);
  const double tolerance = 0.01 * Area(PolygonWithHoles{piece, {}});
  return mirror && !other.empty() && other_uncovered <= best_uncovered + tolerance ? other : best;
}

// Distance (mm) from p to the nearest boundary ring (outline or hole) of `region`.
double DistanceToBoundary(const PolygonWithHoles& region, const Vec& p) {
  double best = std::numeric_limits<double>::infinity();
  auto ring_distance = [&](const Ring& r) {
    for (std::size_t q = 0; q < r.size(); ++q) {
      const Vec a = r[q], b = r[(q + 1) % r.size()];
      const double l2 = (b - a).squaredNorm();
      const double t = l2 > 0.0 ? std::clamp((p - a).dot(b - a) / l2, 0.0, 1.0) : 0.0;
      best = std::min(best, (a + t * (b - a) - p).norm());
    }
  };
  ring_distance(region.outer);
  for (const Ring& hole : region.holes) ring_distance(hole);
  return best;
}

// Flags the edges of `piece` that lie inside `region` (lines shared with other pieces), not on its boundary.
std::vector<bool> SharedEdgeFlags(const Ring& piece, const PolygonWithHoles& region) {
  constexpr double kOnBoundaryMm = 1e-3;
  std::vector<bool> shared(piece.size(), false);
  for (std::size_t k = 0; k < piece.size(); ++k) {
    const Vec m = 0.5 * (piece[k] + piece[(k + 1) % piece.size()]);
    shared[k] = DistanceToBoundary(region, m) > kOnBoundaryMm;
  }
  return shared;
}

// Convex polygon with `sides` edges at evenly spaced normals, each a support line of `ring`: it contains the ring.
Ring Circumscribe(const Ring& ring, int sides) {
  Eigen::Vector2d lo = ring.front(), hi = ring.front();
  for (const Vec& p : ring) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double big = 10.0 * (hi - lo).norm() + 1.0;
  const Vec centre = 0.5 * (lo + hi);
  std::vector<PolygonWithHoles> cell{{{centre + Vec(-big, -big), centre + Vec(big, -big), centre + Vec(big, big),
                                       centre + Vec(-big, big)}, {}}};
  for (int k = 0; k < sides; ++k) {
    const double a = 2.0 * std::numbers::pi * k / sides;
    const Vec n(std::cos(a), std::sin(a)), t(-n.y(), n.x());
    double h = -std::numeric_limits<double>::infinity();
    for (const Vec& p : ring) h = std::max(h, n.dot(p - centre));
    const Vec base = centre + h * n;
    cell = Intersection(cell, {{{base - 3.0 * big * n - 3.0 * big * t, base - 3.0 * big * n + 3.0 * big * t,
                                 base + 3.0 * big * t, base - 3.0 * big * t}, {}}});
  }
  return cell.empty() ? Ring{} : cell.front().outer;
}

// Round holes (many notches) are taken out of the decomposition: the hole gets its own contour ring (a loop joined
// to its neighbours like any other) and the pieces are cut from the region minus a coarse polygon around the ring.
struct Prepared {
  std::vector<PolygonWithHoles> regions;  // what is decomposed
  std::vector<Ring> hole_rings;           // bead centre lines around round holes
};

Prepared SeparateRoundHoles(const PolygonWithHoles& region, const OverlapSpacing& spacing) {
  Prepared out;
  std::vector<PolygonWithHoles> cut_away;
  PolygonWithHoles kept{region.outer, {}};
  for (const Ring& hole : region.holes) {
    Ring solid = hole;
    if (SignedArea(solid) < 0.0) std::reverse(solid.begin(), solid.end());
    const std::vector<PolygonWithHoles> ring = Offset({{solid, {}}}, spacing.boundary_offset_mm);
    const std::vector<PolygonWithHoles> band = Offset({{solid, {}}}, spacing.contour_to_contour_mm);
    const bool round = static_cast<int>(hole.size()) > kRoundHoleVertices;
    std::vector<PolygonWithHoles> others;
    for (const Ring& other : region.holes) {
      if (&other != &hole) others.push_back({other, {}});
    }
    // A ring that would cross the outline or another hole cannot be laid: such holes stay in the decomposition.
    if (!round || ring.size() != 1 || band.size() != 1 ||
        Area(Difference(ring, {{region.outer, {}}})) > 1e-6 || Area(Intersection(ring, others)) > 1e-6) {
      kept.holes.push_back(hole);
      continue;
    }
    out.hole_rings.push_back(ring.front().outer);
    // The coarse polygon holds the hole grown by d2, so piece contours keep >= d2 from the ring's centre line.
    cut_away.push_back({Circumscribe(band.front().outer, kRoundHoleSides), {}});
  }
  out.regions = cut_away.empty() ? std::vector<PolygonWithHoles>{kept} : Difference({kept}, cut_away);
  return out;
}

// The convex pieces of a prepared region, per piece edge whether it is a line shared with another piece, and the
// shared lines, longest first.
struct Pieces {
  std::vector<Ring> pieces;
  std::vector<std::vector<bool>> piece_shared;
  std::vector<SharedEdge> shared;
};

// Decomposes each region of `prepared` into convex pieces (shallow notches filled first); false with the reason in
// `failure` when degenerate geometry defeated the decomposition.
bool DecomposeRegions(const Prepared& prepared, double bead_width_mm, Pieces* out, std::string* failure) {
  for (const PolygonWithHoles& exact : prepared.regions) {
    PolygonWithHoles part{FillShallowNotches(exact.outer, kCurveToleranceFraction * bead_width_mm), {}};
    for (const Ring& hole : exact.holes) {
      part.holes.push_back(FillShallowNotches(hole, kCurveToleranceFraction * bead_width_mm));
    }
    const ConvexDecomposition decomposition = DecomposeConvex(part);
    if (!decomposition.ok()) {
      *failure = decomposition.failure;
      return false;
    }
    const std::vector<Ring>& part_pieces = decomposition.pieces;
    for (SharedEdge edge : FindSharedEdges(part_pieces, part)) {
      edge.piece_a += static_cast<int>(out->pieces.size());
      edge.piece_b += static_cast<int>(out->pieces.size());
      out->shared.push_back(edge);
    }
    out->pieces.insert(out->pieces.end(), part_pieces.begin(), part_pieces.end());
    for (const Ring& piece : part_pieces) out->piece_shared.push_back(SharedEdgeFlags(piece, part));
  }
  std::stable_sort(out->shared.begin(), out->shared.end(), [](const SharedEdge& x, const SharedEdge& y) {
    return (x.b - x.a).norm() > (y.b - y.a).norm();
  });
  return true;
}

// One covering loop per piece (none for a degenerate sliver), then one per round hole's ring.
std::vector<TaggedLoop> CoveringLoops(const Pieces& p, const std::vector<Ring>& hole_rings,
                                      const PatternOptions& options, const OverlapSpacing& spacing) {
  std::vector<TaggedLoop> loops(p.pieces.size());
  for (std::size_t i = 0; i < p.pieces.size(); ++i) {
    if (ConvexHull(p.pieces[i]).size() < 3) continue;  // a degenerate sliver: no path, nothing to join
    const double angle = options.zigzag_auto ? MinimumWidthDirection(p.pieces[i], nullptr) : options.zigzag_angle_rad;
    const bool mirror = options.alternate_start && options.layer_index % 2 == 1;
    loops[i].p = BetterCoveringLoop(p.pieces[i], p.piece_shared[i], angle, options.bead_width_mm, spacing, mirror);
    loops[i].piece.assign(loops[i].p.size(), static_cast<int>(i));
  }
  for (const Ring& ring : hole_rings) {
    loops.push_back(TaggedLoop{ring, std::vector<int>(ring.size(), static_cast<int>(loops.size()))});
  }
  return loops;
}

// Kruskal over the shared lines, longest first: every accepted line joins two loops into one. loops[root] holds the
// joined loop of a tree; a join must keep inside `strict` (or `loose`, see JoinLoops).
void JoinAlongSharedEdges(const Pieces& p, double w, const OverlapSpacing& spacing,
                          const std::vector<PolygonWithHoles>& strict, const std::vector<PolygonWithHoles>& loose,
                          std::vector<TaggedLoop>* loops) {
  std::vector<int> parent(p.pieces.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const SharedEdge& edge : p.shared) {
    const int ra = Find(parent, edge.piece_a), rb = Find(parent, edge.piece_b);
    if (ra == rb || (*loops)[ra].p.size() < 3 || (*loops)[rb].p.size() < 3) continue;
    TaggedLoop joined;
    if (!JoinLoops((*loops)[ra], (*loops)[rb], SharedEdgeSites(edge, w), spacing.zigzag_mm, strict, loose, &joined)) {
      continue;
    }
    (*loops)[ra] = std::move(joined);
    (*loops)[rb] = TaggedLoop{};
    parent[rb] = ra;
  }
}

// Loops still apart (hole rings, pieces across a piece too thin for a path) are joined where they come closest.
void JoinNearestLoops(double w, const OverlapSpacing& spacing, const std::vector<PolygonWithHoles>& strict,
                      const std::vector<PolygonWithHoles>& loose, std::vector<TaggedLoop>* loops) {
  std::vector<TaggedLoop>& l = *loops;
  for (bool progress = true; progress;) {
    progress = false;
    for (std::size_t i = 0; i < l.size() && !progress; ++i) {
      for (std::size_t j = i + 1; j < l.size() && !progress; ++j) {
        if (l[i].p.size() < 3 || l[j].p.size() < 3) continue;
        TaggedLoop joined;
        if (JoinLoops(l[i], l[j], NearestSites(l[i], l[j], 2.0 * w), spacing.zigzag_mm, strict, loose, &joined)) {
          l[i] = std::move(joined);
          l[j] = TaggedLoop{};
          progress = true;
        }
      }
    }
  }
}

}  // namespace

void PlanContinuous(const PolygonWithHoles& region, const PatternOptions& options, const OverlapSpacing& spacing,
                    std::vector<Move2D>* moves, std::vector<std::string>* notes) {
  WAAM_DEMAND(moves != nullptr && notes != nullptr);  // a fallback to the hybrid pattern is always reported
  const Prepared prepared = SeparateRoundHoles(region, spacing);
  Pieces pieces;
  std::string failure;
  if (!DecomposeRegions(prepared, options.bead_width_mm, &pieces, &failure)) {
    // Degenerate geometry defeated the decomposition: this region gets the hybrid baseline, and the plan says so.
    const Eigen::Vector2d c = region.outer.empty() ? Eigen::Vector2d::Zero() : region.outer.front();
    std::ostringstream note;
    note << "the region at (" << c.x() << ", " << c.y() << ") mm was planned with the hybrid pattern: convex "
         << "decomposition failed: " << failure;
    notes->push_back(note.str());
    PlanHybrid(region, options, spacing, moves);
    return;
  }
  const double w = options.bead_width_mm;
  std::vector<TaggedLoop> loops = CoveringLoops(pieces, prepared.hole_rings, options, spacing);
  const std::vector<PolygonWithHoles> strict = Offset({region}, -(spacing.boundary_offset_mm - 0.01));
  const std::vector<PolygonWithHoles> loose = Offset({region}, -0.01);
  JoinAlongSharedEdges(pieces, w, spacing, strict, loose, &loops);
  JoinNearestLoops(w, spacing, strict, loose, &loops);
  // Each remaining loop is one pass; the start rotates along the outline layer by layer and odd layers run the
  // loop the other way, so arc starts and the direction of travel do not stack up.
  const Vec start = PointAlongRing(region.outer, StartFraction(options));
  const bool reverse = options.alternate_start && options.layer_index % 2 == 1;
  for (const TaggedLoop& loop : loops) {
    if (loop.p.size() >= 3) AppendLoop(Simplify(loop.p), start, reverse, moves);
  }
}

}  // namespace waam::planner::internal
