// Exposed voxel faces: their centres in a point hash (nearest face by growing shells of cells) and their normals.
#include "twin/distortion/voxel_faces.h"

namespace waam::twin::internal {

VoxelFaces::VoxelFaces(const VoxelGrid& grid) : VoxelFaces(2.0 * grid.voxel_mm()) {
  const Eigen::Vector3i dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const double s = grid.voxel_mm();
  grid.ForEach([&](const VoxelIndex& idx, const VoxelData&) {
    for (const Eigen::Vector3i& d : dirs) {
      if (grid.Solid(idx + d)) continue;
      centres_.Add(grid.Center(idx) + 0.5 * s * d.cast<double>());
      normal_.push_back(d.cast<double>());
    }
  });
}

VoxelFaces VoxelFaces::Moved(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& u) const {
  VoxelFaces moved(centres_.cell_mm());
  moved.normal_ = normal_;
  for (std::size_t f = 0; f < size(); ++f) {
    const Eigen::Vector3d& c = centres_.point(static_cast<int>(f));
    moved.centres_.Add(c + u(c));
  }
  return moved;
}

}  // namespace waam::twin::internal
