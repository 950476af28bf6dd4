// Footprint columns in the torch frame: a lattice at voxel pitch in the plane perpendicular to the torch axis, each
// lattice cell the column of voxels whose centres project into it, ordered by height along the torch axis.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "twin/deposition/voxel_grid.h"

namespace waam::twin::internal {

// One voxel of a column and the height of its centre along the torch axis, mm.
struct ColumnVoxel {
  VoxelIndex index;
  double height_mm = 0.0;
};

// The torch frame of one path segment: t up the torch, e1 and e2 the lattice axes of the plane perpendicular to it.
// Every voxel centre lies in exactly one lattice cell, so the columns partition the grid: no voxel is in two columns
// and none is skipped. For a torch along a grid axis the lattice is the grid itself and a column is one voxel wide.
class TorchFrame {
 public:
  // `tool_dir_P` is the torch axis in the part frame (any length > 0); `voxel_mm` > 0 the grid pitch.
  TorchFrame(const Eigen::Vector3d& tool_dir_P, double voxel_mm);

  const Eigen::Vector3d& axis() const { return t_; }
  // True when the torch is along a grid axis: the lattice is the grid and a column's voxels are one pitch apart.
  bool aligned() const { return aligned_; }
  // Coordinates of `p_P` (mm) in the lattice plane, mm.
  Eigen::Vector2d Plane(const Eigen::Vector3d& p_P) const { return {p_P.dot(e1_), p_P.dot(e2_)}; }
  // Height of `p_P` (mm) along the torch axis, mm.
  double Height(const Eigen::Vector3d& p_P) const { return p_P.dot(t_); }
  // Appends to `out` the voxels of lattice cell (i0, i1) whose centres lie at heights in [lo_mm, hi_mm] along the
  // torch axis, in increasing height (ties by voxel index, so the order is deterministic).
  void CollectColumn(int i0, int i1, double lo_mm, double hi_mm, std::vector<ColumnVoxel>* out) const;

 private:
  double v_;
  Eigen::Vector3d t_, e1_, e2_;
  int axis_ = 2;           // grid axis nearest t: the column is walked one voxel slab of this axis at a time
  int a0_ = 0, a1_ = 1;    // the other two grid axes
  double reach0_ = 0.0;    // how far (mm) a voxel centre of the cell lies from the column's axis line along a0 / a1
  double reach1_ = 0.0;    // within one slab
  double rise_ = 0.0;      // and along t, mm
  bool aligned_ = false;   // t is a grid axis (to rounding): one voxel per slab
};

}  // namespace waam::twin::internal
