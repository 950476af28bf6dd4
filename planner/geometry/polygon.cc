// Basic measures of rings and regions.
#include "planner/geometry/polygon.h"

#include <cmath>

namespace waam::planner {

double SignedArea(const Ring& ring) {
  const std::size_t n = ring.size();
  if (n < 3) return 0.0;
  double twice = 0.0;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    twice += ring[j].x() * ring[i].y() - ring[i].x() * ring[j].y();
  }
  return 0.5 * twice;
}

double Area(const PolygonWithHoles& region) {
  double area = std::abs(SignedArea(region.outer));
  for (const Ring& hole : region.holes) area -= std::abs(SignedArea(hole));
  return area;
}

double Area(const std::vector<PolygonWithHoles>& regions) {
  double area = 0.0;
  for (const PolygonWithHoles& region : regions) area += Area(region);
  return area;
}

bool PointInRing(const Eigen::Vector2d& p, const Ring& ring) {
  bool inside = false;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d& a = ring[i];
    const Eigen::Vector2d& b = ring[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

double Perimeter(const Ring& ring) {
  double length = 0.0;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) length += (ring[i] - ring[j]).norm();
  return length;
}

}  // namespace waam::planner
