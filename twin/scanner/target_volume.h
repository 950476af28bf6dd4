// The target part as a dense voxel mask (inside / outside), from a triangle mesh or from the planned layer regions.
#pragma once

#include <cstdint>
#include <vector>

#include "planner/mesh/triangle_mesh.h"
#include "planner/path/tool_path.h"
#include "twin/deposition/voxel_grid.h"

namespace waam::twin {

// Inside/outside of the target over a box of voxels aligned with the deposition grid (same voxel size).
class TargetVolume {
 public:
  TargetVolume() = default;
  // Empty mask over voxels lo..hi (inclusive).
  TargetVolume(double voxel_mm, const VoxelIndex& lo, const VoxelIndex& hi);

  // Voxelizes a closed mesh by ray parity along z through each column centre (a voxel is inside when its centre
  // is). Throws InputError if the box has more than `max_voxels` voxels.
  static TargetVolume FromMesh(const planner::TriangleMesh& mesh, double voxel_mm, std::size_t max_voxels);
  // Extrudes each layer's slice regions from the previous layer's z_mm (0 for the first) up to its own z_mm.
  static TargetVolume FromLayers(const planner::Plan& plan, double voxel_mm, std::size_t max_voxels);

  double voxel_mm() const { return voxel_mm_; }
  const VoxelIndex& lo() const { return lo_; }
  const VoxelIndex& hi() const { return hi_; }
  Eigen::Vector3i size() const { return hi_ - lo_ + Eigen::Vector3i::Ones(); }
  bool Inside(const VoxelIndex& v) const;
  void SetInside(const VoxelIndex& v, bool inside);
  // Number of inside voxels and their volume, mm^3.
  std::size_t CountInside() const;

 private:
  std::size_t Offset(const VoxelIndex& v) const;
  double voxel_mm_ = 0.0;
  VoxelIndex lo_ = VoxelIndex::Zero();
  VoxelIndex hi_ = VoxelIndex::Constant(-1);
  std::vector<std::uint8_t> inside_;
};

}  // namespace waam::twin
