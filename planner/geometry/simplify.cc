// Ramer-Douglas-Peucker on closed rings and the Clipper clean-up that keeps simplified regions valid.
#include "planner/geometry/simplify.h"

#include <algorithm>
#include <utility>

#include "planner/geometry/clipper_adapter.h"

namespace waam::planner {
namespace {

using Vec = Eigen::Vector2d;

// Squared distance (mm^2) from p to the segment a-b.
double SquaredSegmentDistance(const Vec& p, const Vec& a, const Vec& b) {
  const Vec ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).squaredNorm();
}

// Marks the points strictly between ring[first] and ring[last] (indices modulo the ring size, last > first) that
// RDP keeps: the farthest from the chord if it lies farther than the tolerance, recursively on both sides.
void MarkKept(const Ring& ring, std::size_t first, std::size_t last, double tolerance2, std::vector<char>* keep) {
  const std::size_t n = ring.size();
  std::vector<std::pair<std::size_t, std::size_t>> stack{{first, last}};
  while (!stack.empty()) {
    const auto [lo, hi] = stack.back();
    stack.pop_back();
    const Vec& a = ring[lo % n];
    const Vec& b = ring[hi % n];
    double farthest = -1.0;
    std::size_t at = lo;
    for (std::size_t i = lo + 1; i < hi; ++i) {
      const double d2 = SquaredSegmentDistance(ring[i % n], a, b);
      if (d2 > farthest) farthest = d2, at = i;
    }
    if (farthest <= tolerance2) continue;
    (*keep)[at % n] = 1;
    stack.emplace_back(lo, at);
    stack.emplace_back(at, hi);
  }
}

}  // namespace

Ring SimplifyRing(const Ring& ring, double tolerance_mm) {
  const std::size_t n = ring.size();
  if (n < 4 || !(tolerance_mm > 0.0)) return ring;
  // A closed ring has no end points: anchor it at its first point and the point farthest from it, and simplify
  // the two chains between them.
  std::size_t far = 0;
  double far2 = -1.0;
  for (std::size_t i = 1; i < n; ++i) {
    const double d2 = (ring[i] - ring[0]).squaredNorm();
    if (d2 > far2) far2 = d2, far = i;
  }
  std::vector<char> keep(n, 0);
  keep[0] = keep[far] = 1;
  const double tolerance2 = tolerance_mm * tolerance_mm;
  MarkKept(ring, 0, far, tolerance2, &keep);
  MarkKept(ring, far, n, tolerance2, &keep);
  Ring out;
  for (std::size_t i = 0; i < n; ++i) {
    if (keep[i]) out.push_back(ring[i]);
  }
  return out;
}

std::vector<PolygonWithHoles> SimplifyRegions(const std::vector<PolygonWithHoles>& regions, double tolerance_mm) {
  ClipperLib::Paths paths;
  for (const PolygonWithHoles& region : regions) {
    const Ring outer = SimplifyRing(region.outer, tolerance_mm);
    if (outer.size() >= 3) paths.push_back(internal::ToPath(outer, true));
    for (const Ring& hole : region.holes) {
      const Ring simple = SimplifyRing(hole, tolerance_mm);
      if (simple.size() >= 3) paths.push_back(internal::ToPath(simple, false));
    }
  }
  // Outers wind +1 and holes -1: the area inside an outer and none of its holes winds +1, a hole's lobe that
  // crossed its outer -1, a twisted lobe of one ring -1. Keeping positive winding keeps exactly the material.
  ClipperLib::Clipper clipper;
  clipper.AddPaths(paths, ClipperLib::ptSubject, true);
  ClipperLib::PolyTree tree;
  clipper.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftPositive, ClipperLib::pftPositive);
  return internal::FromPolyTree(tree);
}

}  // namespace waam::planner
