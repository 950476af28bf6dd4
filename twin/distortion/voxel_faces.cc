// Exposed voxel faces in a spatial hash: nearest face centre by growing shells of cells.
#include "twin/distortion/voxel_faces.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace waam::twin::internal {

VoxelFaces::VoxelFaces(const VoxelGrid& grid) : cell_mm_(2.0 * grid.voxel_mm()) {
  const Eigen::Vector3i dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const double s = grid.voxel_mm();
  grid.ForEach([&](const VoxelIndex& idx, const VoxelData&) {
    for (const Eigen::Vector3i& d : dirs) {
      if (grid.Solid(idx + d)) continue;
      const Eigen::Vector3d c = grid.Center(idx) + 0.5 * s * d.cast<double>();
      cells_[Key(Cell(c))].push_back(static_cast<int>(centre_.size()));
      centre_.push_back(c);
      normal_.push_back(d.cast<double>());
    }
  });
}

VoxelFaces VoxelFaces::Moved(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& u) const {
  VoxelFaces moved;
  moved.cell_mm_ = cell_mm_;
  moved.normal_ = normal_;
  moved.centre_.reserve(centre_.size());
  for (std::size_t f = 0; f < centre_.size(); ++f) {
    moved.centre_.push_back(centre_[f] + u(centre_[f]));
    moved.cells_[Key(moved.Cell(moved.centre_.back()))].push_back(static_cast<int>(f));
  }
  return moved;
}

Eigen::Vector3i VoxelFaces::Cell(const Eigen::Vector3d& p) const {
  return (p / cell_mm_).array().floor().cast<int>();
}

std::uint64_t VoxelFaces::Key(const Eigen::Vector3i& c) {
  return (static_cast<std::uint64_t>(c.x() + (1 << 20)) & 0x1FFFFF) |
         ((static_cast<std::uint64_t>(c.y() + (1 << 20)) & 0x1FFFFF) << 21) |
         ((static_cast<std::uint64_t>(c.z() + (1 << 20)) & 0x1FFFFF) << 42);
}

int VoxelFaces::Nearest(const Eigen::Vector3d& p, double max_mm) const {
  const Eigen::Vector3i c = Cell(p);
  double best2 = std::numeric_limits<double>::infinity();
  int best = -1;
  const int max_ring = static_cast<int>(std::ceil(max_mm / cell_mm_)) + 1;
  for (int ring = 0; ring <= max_ring; ++ring) {
    // Every point of a cell in shell `ring` is at least (ring - 1) cells away: stop once that exceeds the best.
    const double reach = (ring - 1) * cell_mm_;
    if (best >= 0 && reach > 0.0 && reach * reach > best2) break;
    for (int dz = -ring; dz <= ring; ++dz) {
      for (int dy = -ring; dy <= ring; ++dy) {
        for (int dx = -ring; dx <= ring; ++dx) {
          if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != ring) continue;  // the shell only
          const auto it = cells_.find(Key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (int f : it->second) {
            const double d2 = (centre_[f] - p).squaredNorm();
            if (d2 < best2) {
              best2 = d2;
              best = f;
            }
          }
        }
      }
    }
  }
  return best2 <= max_mm * max_mm ? best : -1;
}

}  // namespace waam::twin::internal
