// Internal to the distortion fit: the exposed faces of the deposited voxels, for signed point-to-face distances.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "twin/deposition/voxel_grid.h"
#include "twin/scanner/point_hash.h"

namespace waam::twin::internal {

// Every face of an occupied voxel whose neighbour is empty (not the substrate below z = 0): the faces the twin's scan
// samples (ScanDistortedPart) plus those it does not see (faces of enclosed voids and of the one-voxel slots it
// bridges), which only add candidates to the nearest-face search; exact at any part size, unlike a surface mesh
// coarsened past its facet limit.
class VoxelFaces {
 public:
  explicit VoxelFaces(const VoxelGrid& grid);

  std::size_t size() const { return centres_.size(); }
  // The same faces (same indices and normals) with every centre c moved to c + u(c) by `u` (mm).
  VoxelFaces Moved(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& u) const;
  // Index of the face whose centre is nearest to `p` (mm), searching at most `max_mm` (> 0) away; -1 if none.
  int Nearest(const Eigen::Vector3d& p, double max_mm) const { return centres_.Nearest(p, max_mm); }
  // Signed distance (mm) of `p` to the plane of face `face` (+ on the air side).
  double PlaneDistance(int face, const Eigen::Vector3d& p) const {
    return (p - centres_.point(face)).dot(normal_[face]);
  }
  const Eigen::Vector3d& centre(int face) const { return centres_.point(face); }

 private:
  explicit VoxelFaces(double cell_mm) : centres_(cell_mm) {}
  PointHash centres_;  // face centres in cells of two voxels
  std::vector<Eigen::Vector3d> normal_;
};

}  // namespace waam::twin::internal
