// Ear clipping with hole bridging (the classical method described by Eberly, "Triangulation by ear clipping",
// written here from the description): each hole is joined to the outer ring by a visible bridge, in order of
// decreasing largest x, then ears are cut from the resulting single ring.
#include "planner/geometry/triangulate.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "models/core/error.h"

namespace waam::planner {
namespace {

using Vec = Eigen::Vector2d;

double Cross2d(const Vec& a, const Vec& b) { return a.x() * b.y() - a.y() * b.x(); }
double Orient(const Vec& a, const Vec& b, const Vec& c) { return Cross2d(b - a, c - a); }

// True if segments pq and rs share any point (touching or overlapping counts).
bool SegmentsTouch(const Vec& p, const Vec& q, const Vec& r, const Vec& s) {
  const double d1 = Orient(p, q, r);
  const double d2 = Orient(p, q, s);
  const double d3 = Orient(r, s, p);
  const double d4 = Orient(r, s, q);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  auto on = [](const Vec& a, const Vec& b, const Vec& c, double d) {
    return d == 0.0 && std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
           std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
  };
  return on(p, q, r, d1) || on(p, q, s, d2) || on(r, s, p, d3) || on(r, s, q, d4);
}

// True if direction d leaves vertex v into the interior, for a ring with the interior on the left
// (prev -> v -> next).
bool InSector(const Vec& prev, const Vec& v, const Vec& next, const Vec& d) {
  const Vec e1 = next - v;
  const Vec e0 = prev - v;
  const double turn = Cross2d(e1, e0);
  if (turn > 0) return Cross2d(e1, d) > 0 && Cross2d(d, e0) > 0;
  if (turn < 0) return !(Cross2d(e0, d) >= 0 && Cross2d(d, e1) >= 0);
  return Cross2d(e1, d) > 0;
}

// Joins `hole` (vertex ids, interior of the region on the left) into `ring` by a bridge from the hole's largest-x
// vertex to the nearest ring vertex that sees it. `others` are the holes not yet joined (a bridge must not cross them).
void Bridge(const std::vector<Vec>& pts, std::vector<int>* ring, const std::vector<int>& hole,
            const std::vector<std::vector<int>>& others) {
  std::size_t m_pos = 0;
  for (std::size_t k = 1; k < hole.size(); ++k) {
    const Vec& a = pts[hole[k]];
    const Vec& b = pts[hole[m_pos]];
    if (a.x() > b.x() || (a.x() == b.x() && a.y() < b.y())) m_pos = k;
  }
  const int m = hole[m_pos];
  const Vec& pm = pts[m];
  const Vec& m_prev = pts[hole[(m_pos + hole.size() - 1) % hole.size()]];
  const Vec& m_next = pts[hole[(m_pos + 1) % hole.size()]];

  std::vector<std::size_t> order(ring->size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return (pts[(*ring)[a]] - pm).squaredNorm() < (pts[(*ring)[b]] - pm).squaredNorm();
  });
  auto crosses = [&](const std::vector<int>& loop, const Vec& pp) {
    for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
      const Vec& a = pts[loop[j]];
      const Vec& b = pts[loop[i]];
      if (a == pm || b == pm || a == pp || b == pp) continue;
      if (SegmentsTouch(pm, pp, a, b)) return true;
    }
    return false;
  };
  const std::size_t n = ring->size();
  for (std::size_t pos : order) {
    const Vec& pp = pts[(*ring)[pos]];
    if (pp == pm) continue;
    const Vec& p_prev = pts[(*ring)[(pos + n - 1) % n]];
    const Vec& p_next = pts[(*ring)[(pos + 1) % n]];
    if (!InSector(p_prev, pp, p_next, pm - pp) || !InSector(m_prev, pm, m_next, pp - pm)) continue;
    if (crosses(*ring, pp) || crosses(hole, pp)) continue;
    bool blocked = false;
    for (const std::vector<int>& other : others) blocked = blocked || crosses(other, pp);
    if (blocked) continue;
    // Splice: ... P, M, hole after M ..., M, P, ...
    std::vector<int> spliced;
    spliced.reserve(n + hole.size() + 2);
    spliced.insert(spliced.end(), ring->begin(), ring->begin() + pos + 1);
    for (std::size_t k = 0; k <= hole.size(); ++k) spliced.push_back(hole[(m_pos + k) % hole.size()]);
    spliced.insert(spliced.end(), ring->begin() + pos, ring->end());
    *ring = std::move(spliced);
    return;
  }
  WAAM_THROW("cannot triangulate a region: no bridge from the hole at (" << pm.x() << ", " << pm.y()
                                                                          << ") mm to its outer ring (rings overlap?)");
}

}  // namespace

std::vector<std::array<int, 3>> TriangulateRegion(const PolygonWithHoles& region) {
  std::vector<Vec> pts(region.outer.begin(), region.outer.end());
  WAAM_THROW_UNLESS(region.outer.size() >= 3, "cannot triangulate a region whose outer ring has "
                                                  << region.outer.size() << " points (needs >= 3)");
  std::vector<int> ring(region.outer.size());
  std::iota(ring.begin(), ring.end(), 0);
  if (SignedArea(region.outer) < 0) std::reverse(ring.begin(), ring.end());

  std::vector<std::vector<int>> holes;
  for (const Ring& hole : region.holes) {
    WAAM_THROW_UNLESS(hole.size() >= 3, "cannot triangulate a hole with " << hole.size() << " points (needs >= 3)");
    std::vector<int> ids(hole.size());
    std::iota(ids.begin(), ids.end(), static_cast<int>(pts.size()));
    pts.insert(pts.end(), hole.begin(), hole.end());
    if (SignedArea(hole) > 0) std::reverse(ids.begin(), ids.end());  // holes clockwise
    holes.push_back(std::move(ids));
  }
  // Bridge holes in order of decreasing largest x (ties by index), so each bridge runs to already-joined geometry.
  auto max_x = [&](const std::vector<int>& h) {
    double x = -INFINITY;
    for (int id : h) x = std::max(x, pts[id].x());
    return x;
  };
  std::stable_sort(holes.begin(), holes.end(),
                   [&](const std::vector<int>& a, const std::vector<int>& b) { return max_x(a) > max_x(b); });
  for (std::size_t h = 0; h < holes.size(); ++h) {
    const std::vector<std::vector<int>> others(holes.begin() + h + 1, holes.end());
    Bridge(pts, &ring, holes[h], others);
  }

  // Ear clipping on a doubly linked list; an ear is a strictly convex corner whose triangle contains no other
  // ring vertex (vertices at the same place as a corner, the two ends of a bridge, do not block).
  const std::size_t n = ring.size();
  std::vector<std::size_t> prev(n), next(n);
  for (std::size_t i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  double scale = 0.0;
  for (const Vec& p : pts) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  const double eps = 1e-14 * std::max(1.0, scale * scale);
  auto is_ear = [&](std::size_t i) {
    const Vec& a = pts[ring[prev[i]]];
    const Vec& b = pts[ring[i]];
    const Vec& c = pts[ring[next[i]]];
    if (Orient(a, b, c) <= eps) return false;
    for (std::size_t k = next[next[i]]; k != prev[i]; k = next[k]) {
      const Vec& p = pts[ring[k]];
      if (p == a || p == b || p == c) continue;
      if (Orient(a, b, p) >= 0 && Orient(b, c, p) >= 0 && Orient(c, a, p) >= 0) return false;
    }
    return true;
  };
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(n);
  std::size_t remaining = n;
  std::size_t i = 0;
  std::size_t misses = 0;
  while (remaining > 3) {
    if (is_ear(i)) {
      triangles.push_back({ring[prev[i]], ring[i], ring[next[i]]});
      next[prev[i]] = next[i];
      prev[next[i]] = prev[i];
      --remaining;
      i = prev[i];
      misses = 0;
      continue;
    }
    i = next[i];
    WAAM_THROW_UNLESS(++misses <= remaining, "cannot triangulate a region: no ear left among "
                                                 << remaining << " vertices (self-intersecting or overlapping rings?)");
  }
  triangles.push_back({ring[prev[i]], ring[i], ring[next[i]]});
  return triangles;
}

}  // namespace waam::planner
