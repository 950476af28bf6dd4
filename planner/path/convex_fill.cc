// Contour + zigzag closed loop for one convex piece (Ding et al. 2014, 3.2 steps 1-5, Fig. 7).
//
// Ding offsets the polygon's "left chain" to bound the zigzag and walks: left chain contour, then the zigzag whose
// turnarounds on the right lie on the contour. This is the mirror image: with n the normal of the raster direction
// ("up") and B, T the lowest and highest points of the contour ring C (the piece inset by w/2):
//   B -> right chain of C -> T -> down the left chain to the first raster -> zigzag downwards, where the left ends
//   of the rasters lie on C (the left turnarounds follow C) and the right ends lie on Z = C inset by d1 (the right
//   turnarounds follow Z, d1 inside the contour just laid) -> down the left chain to B.
// The number of rasters is even so the zigzag ends on the left chain and the loop closes at B; the count and the
// gaps to the contour are chosen so the pitch stays near l (ChooseRasterLevels; Ding spreads them evenly over Z).
// Sides shared with a neighbouring piece are not walls: there C runs l/2 inside and Z l inside C (not w/2 and d1),
// so the beads of two pieces lie l apart across their shared line (see continuous_pattern.cc).
#include "planner/path/convex_fill.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "planner/geometry/clipper_adapter.h"

namespace waam::planner::internal {
namespace {

using Vec = Eigen::Vector2d;

// Rasters sit this far (mm) inside the top and bottom of Z so they cut Z's chains, not run along a flush edge.
constexpr double kLevelInsetMm = 1e-4;

struct Frame {
  Vec u, n;
  double h(const Vec& p) const { return n.dot(p); }
  double x(const Vec& p) const { return u.dot(p); }
};

// The largest ring of an inward offset of a convex ring (convex up to Clipper's rounding); empty if none.
Ring InsetConvex(const Ring& ring, double inset_mm) {
  Ring best;
  double best_area = 0.0;
  for (const PolygonWithHoles& r : Offset({PolygonWithHoles{ring, {}}}, -inset_mm)) {
    if (Area(r) > best_area) best_area = Area(r), best = r.outer;
  }
  return best;
}

// The convex CCW `ring` with edge k moved inward by inset_mm[k]: the intersection of the shifted edges' half-planes
// (Clipper), so an edge that the others overtake simply drops out. Empty if nothing is left.
Ring InsetEdges(const Ring& ring, const std::vector<double>& inset_mm) {
  Vec lo = ring.front(), hi = ring.front();
  for (const Vec& p : ring) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double big = 4.0 * (hi - lo).norm() + 1.0;
  std::vector<PolygonWithHoles> cell{{{lo - Vec(big, big), Vec(hi.x() + big, lo.y() - big), hi + Vec(big, big),
                                       Vec(lo.x() - big, hi.y() + big)}, {}}};
  const std::size_t n = ring.size();
  for (std::size_t k = 0; k < n && !cell.empty(); ++k) {
    const Vec a = ring[k], b = ring[(k + 1) % n];
    if ((b - a).norm() < 1e-9) continue;
    const Vec t = (b - a).normalized(), inward(-t.y(), t.x());
    const Vec base = a + inset_mm[k] * inward;
    // A square on the inner side of the shifted edge line, larger than the ring.
    const Vec far = 6.0 * big * t, deep = 6.0 * big * inward;
    cell = Intersection(cell, {{{base - far, base + far, base + far + deep, base - far + deep}, {}}});
  }
  Ring best;
  double best_area = 0.0;
  for (const PolygonWithHoles& r : cell) {
    if (Area(r) > best_area) best_area = Area(r), best = r.outer;
  }
  if (!best.empty() && SignedArea(best) < 0.0) std::reverse(best.begin(), best.end());
  return best;
}

// Rotates `ring` (CCW) so it starts at its lowest point (ties: the one farthest along u) and returns the index of
// the first highest point met walking CCW from there: [0, top] is the right chain, [top, n) + 0 the left chain.
int RotateToBottom(const Frame& f, Ring* ring) {
  const double tol = 1e-7;
  int bottom = 0;
  for (int i = 1; i < static_cast<int>(ring->size()); ++i) {
    const Vec& p = (*ring)[i];
    const Vec& b = (*ring)[bottom];
    if (f.h(p) < f.h(b) - tol || (std::abs(f.h(p) - f.h(b)) <= tol && f.x(p) > f.x(b))) bottom = i;
  }
  std::rotate(ring->begin(), ring->begin() + bottom, ring->end());
  int top = 0;
  for (int i = 1; i < static_cast<int>(ring->size()); ++i) {
    if (f.h((*ring)[i]) > f.h((*ring)[top]) + tol) top = i;
  }
  return top;
}

// The part of a chain (h non-increasing along it) between levels h_hi >= h_lo, with the end points interpolated.
std::vector<Vec> Between(const Frame& f, const std::vector<Vec>& chain, double h_hi, double h_lo) {
  std::vector<Vec> out;
  auto push = [&](const Vec& p) {
    if (out.empty() || (p - out.back()).norm() > 1e-9) out.push_back(p);
  };
  auto at = [&](const Vec& a, const Vec& b, double level) {
    const double ha = f.h(a), hb = f.h(b);
    const double t = ha - hb > 1e-15 ? std::clamp((ha - level) / (ha - hb), 0.0, 1.0) : 0.0;
    return Vec(a + t * (b - a));
  };
  for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
    const Vec& a = chain[i];
    const Vec& b = chain[i + 1];
    const double top = std::min(f.h(a), h_hi), bottom = std::max(f.h(b), h_lo);
    if (top < bottom) continue;
    push(at(a, b, top));
    push(at(a, b, bottom));
  }
  return out;
}

void Append(const std::vector<Vec>& points, Ring* loop) {
  for (const Vec& p : points) {
    if (loop->empty() || (p - loop->back()).norm() > 1e-9) loop->push_back(p);
  }
}

// How the zigzag fills a strip of height `range_mm` between the top and bottom of Z (Z is d1 inside the contour).
struct RasterLevels {
  int lines = 2;              // even: the loop runs down the left chain after the zigzag and closes at B
  double pitch_mm = 0.0;      // between neighbouring rasters
  double extra_gap_mm = 0.0;  // added to d1 at the top and at the bottom of the zigzag
};

// The loop needs an even number of rasters, so a strip holds either a raster too few (pitch above l: a valley
// between beads) or one too many (pitch below l: a bump). Ding's even spreading over the strip can put rasters at a
// third of l in a narrow piece, so nearly three beads of metal land where one belongs, and the same piece repeats
// on every layer. Here the two even counts around range/l are compared: with the larger count the gaps to the
// contour may grow from d1 up to l (the existing model's spacing, 003 Table 9) before the pitch drops below l; the
// count whose pitch is nearer l (by ratio) is kept.
RasterLevels ChooseRasterLevels(double range_mm, const OverlapSpacing& spacing) {
  const double l = spacing.zigzag_mm;
  const double max_extra = std::max(0.0, l - spacing.contour_to_zigzag_mm);
  const int exact = std::max(2, static_cast<int>(std::ceil(range_mm / l - 1e-9)) + 1);  // fewest with pitch <= l
  const int more = exact % 2 == 0 ? exact : exact + 1;
  RasterLevels dense;
  dense.lines = more;
  dense.extra_gap_mm = std::clamp(0.5 * (range_mm - (more - 1) * l), 0.0, max_extra);
  if (range_mm - 2.0 * dense.extra_gap_mm <= 0.0) dense.extra_gap_mm = 0.0;
  dense.pitch_mm = (range_mm - 2.0 * dense.extra_gap_mm) / (more - 1);
  if (more - 2 < 2) return dense;
  RasterLevels sparse;
  sparse.lines = more - 2;
  sparse.pitch_mm = range_mm / (sparse.lines - 1);
  return std::abs(std::log(sparse.pitch_mm / l)) < std::abs(std::log(dense.pitch_mm / l)) ? sparse : dense;
}

}  // namespace

Ring ConvexPieceLoop(const Ring& piece, double angle_rad, const OverlapSpacing& spacing,
                     const std::vector<bool>& shared) {
  const bool any_shared = std::find(shared.begin(), shared.end(), true) != shared.end();
  Ring contour;
  Ring zig;
  if (any_shared && shared.size() == piece.size()) {
    // Along a shared line the neighbour's bead lies l/2 beyond it, so this piece's bead is laid l/2 inside and the
    // rasters keep the zigzag spacing l from it (003 eq. 3.15: l between neighbouring beads; d1 < l is the gap to a
    // contour on a free wall, whose outer side sags).
    const double l = spacing.zigzag_mm;
    std::vector<double> c_inset(piece.size()), z_inset(piece.size());
    for (std::size_t k = 0; k < piece.size(); ++k) {
      c_inset[k] = shared[k] ? 0.5 * l : spacing.boundary_offset_mm;
      z_inset[k] = c_inset[k] + (shared[k] ? l : spacing.contour_to_zigzag_mm);
    }
    contour = InsetEdges(piece, c_inset);
    zig = InsetEdges(piece, z_inset);
  } else {
    contour = InsetConvex(piece, spacing.boundary_offset_mm);
    if (contour.size() >= 3) zig = InsetConvex(contour, spacing.contour_to_zigzag_mm);
  }
  if (contour.size() < 3) return {};
  const Frame f{Vec(std::cos(angle_rad), std::sin(angle_rad)), Vec(-std::sin(angle_rad), std::cos(angle_rad))};
  const int top = RotateToBottom(f, &contour);

  if (zig.size() < 3) return contour;
  const int zig_top = RotateToBottom(f, &zig);
  const double z_hi = f.h(zig[zig_top]) - kLevelInsetMm, z_lo = f.h(zig[0]) + kLevelInsetMm;
  // A zigzag strip thinner than a quarter step-over adds little but doubled metal: the contour alone fills it.
  if (z_hi - z_lo < 0.25 * spacing.zigzag_mm) return contour;
  const RasterLevels levels = ChooseRasterLevels(z_hi - z_lo, spacing);
  const int lines = levels.lines;
  const double first_level = z_hi - levels.extra_gap_mm;
  auto level = [&](int k) { return first_level - k * levels.pitch_mm; };  // k = 0 .. lines-1, top to bottom

  std::vector<Vec> left(contour.begin() + top, contour.end());  // C's left chain, T down to B
  left.push_back(contour.front());
  std::vector<Vec> zig_right(zig.begin(), zig.begin() + zig_top + 1);  // Z's right chain, top down to bottom
  std::reverse(zig_right.begin(), zig_right.end());
  const double inf = std::numeric_limits<double>::infinity();

  Ring loop(contour.begin(), contour.begin() + top + 1);  // B up the right chain to T
  Append(Between(f, left, inf, level(0)), &loop);            // T down to the first raster
  for (int k = 0; k < lines; ++k) {
    if (k % 2 == 0) {
      // Raster to the right end on Z, then (if more follow) down Z's right chain to the next raster.
      const std::vector<Vec> turn = Between(f, zig_right, level(k), k + 1 < lines ? level(k + 1) : level(k));
      Append(turn, &loop);
    } else {
      // Raster back to the left end on C, then down C's left chain to the next raster (or to B after the last).
      Append(Between(f, left, level(k), k + 1 < lines ? level(k + 1) : -inf), &loop);
    }
  }
  if (loop.size() > 1 && (loop.back() - loop.front()).norm() <= 1e-9) loop.pop_back();
  return loop;
}

}  // namespace waam::planner::internal
