// A bucket grid over a point cloud for radius and nearest-point queries (scan neighbourhoods, outlier removal, face
// search), and the integer cell keys every 3D bucket hash of the twin shares.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace waam::twin {

// The cell (floor(p / cell_mm) on each axis) of a grid of cubic cells of `cell_mm` (> 0) that holds `p` (mm).
inline Eigen::Vector3i CellOf(const Eigen::Vector3d& p, double cell_mm) {
  return Eigen::Vector3i(static_cast<int>(std::floor(p.x() / cell_mm)), static_cast<int>(std::floor(p.y() / cell_mm)),
                         static_cast<int>(std::floor(p.z() / cell_mm)));
}

// Hash key of an integer cell: 21 bits an axis (x lowest), one-to-one for coordinates in [-2^20, 2^20).
inline std::uint64_t CellKey(const Eigen::Vector3i& c) {
  return (static_cast<std::uint64_t>(c.x() + (1 << 20)) & 0x1FFFFF) |
         ((static_cast<std::uint64_t>(c.y() + (1 << 20)) & 0x1FFFFF) << 21) |
         ((static_cast<std::uint64_t>(c.z() + (1 << 20)) & 0x1FFFFF) << 42);
}

// The cell of a CellKey (its inverse in that range).
inline Eigen::Vector3i CellOfKey(std::uint64_t key) {
  return Eigen::Vector3i(static_cast<int>(key & 0x1FFFFF) - (1 << 20),
                         static_cast<int>((key >> 21) & 0x1FFFFF) - (1 << 20),
                         static_cast<int>((key >> 42) & 0x1FFFFF) - (1 << 20));
}

// Points hashed into cubic cells of `cell_mm` (> 0); point i is the i-th given or added. Throws InputError for a
// cell <= 0.
class PointHash {
 public:
  explicit PointHash(double cell_mm);
  PointHash(std::vector<Eigen::Vector3d> points, double cell_mm);

  // Adds `p` (mm) and returns its index.
  int Add(const Eigen::Vector3d& p) {
    const int i = static_cast<int>(points_.size());
    cells_[CellKey(CellOf(p, cell_))].push_back(i);
    points_.push_back(p);
    return i;
  }
  std::size_t size() const { return points_.size(); }
  double cell_mm() const { return cell_; }
  const Eigen::Vector3d& point(int i) const { return points_[i]; }

  // Calls f(i) for every point i within `radius` (mm) of `p` (p itself included when it is in the cloud). `f` may
  // return bool: false stops the search there. Returns false when `f` stopped it, true when every point was visited.
  template <typename F>
  bool ForEachNear(const Eigen::Vector3d& p, double radius, F&& f) const {
    const Eigen::Vector3i c = CellOf(p, cell_);
    const int reach = static_cast<int>(std::ceil(radius / cell_));
    for (int dz = -reach; dz <= reach; ++dz) {
      for (int dy = -reach; dy <= reach; ++dy) {
        for (int dx = -reach; dx <= reach; ++dx) {
          auto it = cells_.find(CellKey(c + Eigen::Vector3i(dx, dy, dz)));
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

  // Index of the point nearest to `p` (mm) within `max_mm` (> 0), -1 if none; of equally near points the first found
  // in the search order (shells of cells around p's cell, growing).
  int Nearest(const Eigen::Vector3d& p, double max_mm) const;

 private:
  double cell_;
  std::vector<Eigen::Vector3d> points_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

// Radius outlier removal, as scanner software does before a comparison: the indices of the points of `points` that
// have at least `min_neighbours` other points within `radius_mm` (> 0). A speck of a few points far from any
// surface (a stray voxel, spatter) is dropped; a surface sampled finer than the radius keeps every point.
std::vector<std::size_t> DenseScanPoints(const std::vector<Eigen::Vector3d>& points, double radius_mm,
                                         int min_neighbours);

}  // namespace waam::twin
