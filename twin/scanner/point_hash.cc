// Bucket grid over a point cloud: radius and nearest-point queries, and radius outlier removal.
#include "twin/scanner/point_hash.h"

#include <limits>

#include "models/core/error.h"

namespace waam::twin {

PointHash::PointHash(double cell_mm) : cell_(cell_mm) {
  WAAM_THROW_UNLESS(cell_mm > 0.0, "point hash cell " << cell_mm << " mm: must be > 0");
}

PointHash::PointHash(std::vector<Eigen::Vector3d> points, double cell_mm) : PointHash(cell_mm) {
  points_ = std::move(points);
  for (std::size_t i = 0; i < points_.size(); ++i) {
    cells_[CellKey(CellOf(points_[i], cell_))].push_back(static_cast<int>(i));
  }
}

int PointHash::CountNear(const Eigen::Vector3d& p, double radius, int cap) const {
  int count = 0;
  ForEachNear(p, radius, [&](int) { return ++count < cap; });
  return count;
}

int PointHash::Nearest(const Eigen::Vector3d& p, double max_mm) const {
  const Eigen::Vector3i c = CellOf(p, cell_);
  double best2 = std::numeric_limits<double>::infinity();
  int best = -1;
  const int max_ring = static_cast<int>(std::ceil(max_mm / cell_)) + 1;
  for (int ring = 0; ring <= max_ring; ++ring) {
    // Every point of a cell in shell `ring` is at least (ring - 1) cells away: stop once that exceeds the best.
    const double reach = (ring - 1) * cell_;
    if (best >= 0 && reach > 0.0 && reach * reach > best2) break;
    for (int dz = -ring; dz <= ring; ++dz) {
      for (int dy = -ring; dy <= ring; ++dy) {
        for (int dx = -ring; dx <= ring; ++dx) {
          if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != ring) continue;  // the shell only
          const auto it = cells_.find(CellKey(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (int i : it->second) {
            const double d2 = (points_[i] - p).squaredNorm();
            if (d2 < best2) {
              best2 = d2;
              best = i;
            }
          }
        }
      }
    }
  }
  return best2 <= max_mm * max_mm ? best : -1;
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
