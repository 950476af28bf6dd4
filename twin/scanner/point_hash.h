// A bucket grid over a point cloud for radius queries (scan neighbourhoods, outlier removal).
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace waam::twin {

// Points hashed into cubic cells of `cell_mm` (> 0); the cloud must outlive the hash and not change.
class PointHash {
 public:
  PointHash(const std::vector<Eigen::Vector3d>& points, double cell_mm);

  // Calls f(i) for every point i within `radius` (mm) of `p` (p itself included when it is in the cloud). `f` may
  // return bool: false stops the search there. Returns false when `f` stopped it, true when every point was visited.
  template <typename F>
  bool ForEachNear(const Eigen::Vector3d& p, double radius, F&& f) const {
    const Eigen::Vector3i c = Cell(p);
    const int reach = static_cast<int>(std::ceil(radius / cell_));
    for (int dz = -reach; dz <= reach; ++dz) {
      for (int dy = -reach; dy <= reach; ++dy) {
        for (int dx = -reach; dx <= reach; ++dx) {
          auto it = cells_.find(Key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (int i : it->second) {
            if ((points_[i] - p).squaredNorm() <= radius * radius) {
              if constexpr (std::is_same_v<std::invoke_result_t<F&, int>, bool>) {
                if (!f(i)) return false;
              } else {
                f(i);
              }
            }
          }
        }
      }
    }
    return true;
  }

  // Number of points within `radius` (mm) of `p`, counted up to `cap` (the count stops there).
  int CountNear(const Eigen::Vector3d& p, double radius, int cap) const;

 private:
  Eigen::Vector3i Cell(const Eigen::Vector3d& p) const {
    return Eigen::Vector3i(static_cast<int>(std::floor(p.x() / cell_)), static_cast<int>(std::floor(p.y() / cell_)),
                           static_cast<int>(std::floor(p.z() / cell_)));
  }
  static std::uint64_t Key(const Eigen::Vector3i& c) {
    return (static_cast<std::uint64_t>(c.x() + (1 << 20)) & 0x1FFFFF) |
           ((static_cast<std::uint64_t>(c.y() + (1 << 20)) & 0x1FFFFF) << 21) |
           ((static_cast<std::uint64_t>(c.z() + (1 << 20)) & 0x1FFFFF) << 42);
  }
  const std::vector<Eigen::Vector3d>& points_;
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

// Radius outlier removal, as scanner software does before a comparison: the indices of the points of `points` that
// have at least `min_neighbours` other points within `radius_mm` (> 0). A speck of a few points far from any
// surface (a stray voxel, spatter) is dropped; a surface sampled finer than the radius keeps every point.
std::vector<std::size_t> DenseScanPoints(const std::vector<Eigen::Vector3d>& points, double radius_mm,
                                         int min_neighbours);

}  // namespace waam::twin
