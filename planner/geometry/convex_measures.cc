// Measures of convex polygons: convexity, hull, minimum width (rotating calipers) and the lines pieces share.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "models/core/error.h"
#include "planner/geometry/convex_decomposition.h"
#include "planner/geometry/ring_math.h"

namespace waam::planner {

using internal::At;
using internal::BoundingDiagonal;
using internal::Cross;
using internal::Turn;
using Vec = Eigen::Vector2d;

std::vector<SharedEdge> FindSharedEdges(const std::vector<Ring>& pieces, const PolygonWithHoles& region) {
  const double tol = 1e-7 * std::max(1.0, BoundingDiagonal(region));
  auto on_boundary = [&](const Vec& q) {
    auto near_ring = [&](const Ring& r) {
      for (int k = 0; k < static_cast<int>(r.size()); ++k) {
        const Vec a = r[k], b = At(r, k + 1);
        const double l2 = (b - a).squaredNorm();
        const double t = l2 > 0.0 ? std::clamp((q - a).dot(b - a) / l2, 0.0, 1.0) : 0.0;
        if ((a + t * (b - a) - q).norm() < 1e3 * tol) return true;
      }
      return false;
    };
    if (near_ring(region.outer)) return true;
    return std::any_of(region.holes.begin(), region.holes.end(), near_ring);
  };
  std::vector<SharedEdge> shared;
  for (int i = 0; i < static_cast<int>(pieces.size()); ++i) {
    for (int j = i + 1; j < static_cast<int>(pieces.size()); ++j) {
      SharedEdge best;
      double best_len = 0.0;
      for (int ei = 0; ei < static_cast<int>(pieces[i].size()); ++ei) {
        const Vec a = pieces[i][ei], b = At(pieces[i], ei + 1);
        const double len = (b - a).norm();
        if (len <= tol) continue;
        const Vec u = (b - a) / len;
        for (int ej = 0; ej < static_cast<int>(pieces[j].size()); ++ej) {
          const Vec c = pieces[j][ej], d = At(pieces[j], ej + 1);
          if (u.dot(d - c) >= 0.0 || std::abs(Cross(u, c - a)) > tol || std::abs(Cross(u, d - a)) > tol) continue;
          const double lo = std::max(0.0, std::min((c - a).dot(u), (d - a).dot(u)));
          const double hi = std::min(len, std::max((c - a).dot(u), (d - a).dot(u)));
          if (hi - lo > best_len + tol) {
            best_len = hi - lo;
            best = SharedEdge{i, j, a + lo * u, a + hi * u, false};
          }
        }
      }
      if (best_len <= 1e3 * tol) continue;
      if (!on_boundary(best.a) && on_boundary(best.b)) std::swap(best.a, best.b);
      best.a_on_boundary = on_boundary(best.a);
      shared.push_back(best);
    }
  }
  std::stable_sort(shared.begin(), shared.end(), [](const SharedEdge& x, const SharedEdge& y) {
    return (x.b - x.a).norm() > (y.b - y.a).norm();
  });
  return shared;
}

bool IsConvex(const Ring& ring, double tolerance_rad) {
  const int n = static_cast<int>(ring.size());
  if (n < 3) return false;
  const double sign = SignedArea(ring) >= 0.0 ? 1.0 : -1.0;
  double total_turn = 0.0;
  for (int i = 0; i < n; ++i) {
    const double turn = sign * Turn(ring, i);
    if (turn < -tolerance_rad) return false;
    total_turn += turn;
  }
  return std::abs(total_turn - 2.0 * std::numbers::pi) < 1e-6;  // a star drawn with one ring turns 4 pi
}

Ring ConvexHull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(),
            [](const Vec& a, const Vec& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  Ring hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // lower chain
    while (k >= 2 && Cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && Cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

double MinimumWidthDirection(const Ring& convex, double* width_mm) {
  const Ring hull = ConvexHull(convex);
  const int n = static_cast<int>(hull.size());
  WAAM_THROW_UNLESS(n >= 3, "minimum width direction: polygon has " << n
                                                                     << " non-collinear distinct points: need >= 3");
  // Rotating calipers: for edge i the farthest vertex j only moves forward as i does (Ding Lemma 1: the strip of
  // least width has one side flush with an edge, so only the n edge directions need to be tried).
  auto height = [&](int i, int j) {
    const Vec e = (At(hull, i + 1) - hull[i]).normalized();
    return Cross(e, At(hull, j) - hull[i]);
  };
  int j = 1;
  double best_width = std::numeric_limits<double>::infinity();
  int best_edge = 0;
  for (int i = 0; i < n; ++i) {
    while (height(i, j + 1) >= height(i, j) - 1e-15) {
      j = (j + 1) % n;
      if (j == i) break;
    }
    const double w = height(i, j);
    if (w < best_width) best_width = w, best_edge = i;
  }
  if (width_mm != nullptr) *width_mm = best_width;
  const Vec e = At(hull, best_edge + 1) - hull[best_edge];
  double angle = std::atan2(e.y(), e.x());
  if (angle < 0.0) angle += std::numbers::pi;
  if (angle >= std::numbers::pi) angle -= std::numbers::pi;
  return angle;
}

}  // namespace waam::planner

