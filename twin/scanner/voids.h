// Voids and valleys of the simulated part inside the target volume, as a milled section would show them.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "twin/deposition/voxel_grid.h"
#include "twin/scanner/target_volume.h"

namespace waam::twin {

// One connected empty region.
struct EmptyRegion {
  std::size_t voxels = 0;
  double volume_mm3 = 0.0;
  double length_mm = 0.0;                             // extent along its principal axis in XY, mm
  Eigen::Vector3d centroid_mm = Eigen::Vector3d::Zero();
};

struct VoidReport {
  // Enclosed: empty voxels inside the target that a horizontal cut at their height shows surrounded by metal
  // (not connected within the cut to the air around the part), with metal above them.
  std::vector<EmptyRegion> voids;
  // The same but open to the top (no metal above): valleys and pits of the top surface.
  std::vector<EmptyRegion> valleys;
  double void_volume_mm3 = 0.0;
  double void_max_length_mm = 0.0;
  double valley_volume_mm3 = 0.0;
  double valley_max_length_mm = 0.0;
  // Enclosed regions and valleys smaller than the minimum volume: voxel-scale gaps, counted here only.
  double min_volume_mm3 = 0.0;
  std::size_t small_regions = 0;
  double small_volume_mm3 = 0.0;
};

// Finds voids and valleys (6-connected regions, largest first) of `grid` inside `target` (same voxel size).
// Regions smaller than `min_volume_mm3` are not listed, only counted in `small_regions` / `small_volume_mm3`.
// Throws InputError if the voxel sizes differ.
VoidReport FindVoids(const VoxelGrid& grid, const TargetVolume& target, double min_volume_mm3 = 0.0);

// The enclosed empty regions a horizontal cut at height `z_mm` shows (a milled section, 003 sec. 4.4.2): 4-connected
// cells of the cut inside the target that the air around the part cannot reach within the cut. Longest first.
std::vector<EmptyRegion> SectionVoids(const VoxelGrid& grid, const TargetVolume& target, double z_mm);

}  // namespace waam::twin
