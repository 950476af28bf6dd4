// Bucket grid over a point cloud and radius outlier removal.
#include "twin/scanner/point_hash.h"

#include "models/core/error.h"

namespace waam::twin {

PointHash::PointHash(const std::vector<Eigen::Vector3d>& points, double cell_mm) : points_(points), cell_(cell_mm) {
  WAAM_THROW_UNLESS(cell_mm > 0.0, "point hash cell " << cell_mm << " mm: must be > 0");
  for (std::size_t i = 0; i < points.size(); ++i) cells_[Key(Cell(points[i]))].push_back(static_cast<int>(i));
}

int PointHash::CountNear(const Eigen::Vector3d& p, double radius, int cap) const {
  int count = 0;
  ForEachNear(p, radius, [&](int) { return ++count < cap; });
  return count;
}

std::vector<std::size_t> DenseScanPoints(const std::vector<Eigen::Vector3d>& points, double radius_mm,
                                         int min_neighbours) {
  WAAM_THROW_UNLESS(radius_mm > 0.0, "scan outlier radius " << radius_mm << " mm: must be > 0");
  const PointHash hash(points, radius_mm);
  std::vector<std::size_t> keep;
  keep.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    // The point itself is counted too.
    if (hash.CountNear(points[i], radius_mm, min_neighbours + 1) > min_neighbours) keep.push_back(i);
  }
  return keep;
}

}  // namespace waam::twin
