// Internal to the distortion model: the coarse hexahedral mesh of the deposited part with per-element strain data.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "models/distortion/distortion_params.h"
#include "twin/deposition/voxel_grid.h"
#include "twin/distortion/deposit_history.h"

namespace waam::twin::internal {

// One hexahedron of edge h: element (I, J, K) covers [I h, (I+1) h) x ... in the part frame.
struct HexElement {
  Eigen::Vector3i ijk = Eigen::Vector3i::Zero();
  double layer = 0.0;                               // mean layer of its voxels
  double strain = 0.0;                              // mean in-layer inherent strain of its voxels, 1
  Eigen::Vector3d dir = Eigen::Vector3d::UnitZ();   // mean build direction (unit)
  Eigen::Vector3d center = Eigen::Vector3d::Zero(); // mm
  int group = 0;                                    // activation group
  std::array<int, 8> nodes{};                       // node ids, hex8 order (x fastest, then y, then z)
};

struct HexMesh {
  double h_mm = 0.0;
  std::vector<HexElement> elements;
  std::vector<Eigen::Vector3i> node_ijk;            // node (I, J, K) at (I h, J h, K h)
  std::unordered_map<std::uint64_t, int> node_id;
  int groups = 1;
};

// Elements of `factor` voxels per edge: active where at least half the fine voxels are metal. Groups split the
// layers into `groups` equal ranges. A voxel's strain is params.StrainAt(q) times layer_factor[its layer] when
// `layer_factor` is not empty (one per plan layer).
HexMesh BuildHexMesh(const VoxelGrid& grid, const DepositHistory& history, const models::DistortionParams& params,
                     int factor, int groups, const std::vector<double>& layer_factor = {});

// Element ids of `active` (mask over mesh.elements) connected through shared nodes to an element on the substrate
// (K = 0). Others are cleared in `active`; returns how many were cleared.
std::size_t KeepConnectedToSubstrate(const HexMesh& mesh, std::vector<std::uint8_t>* active);

}  // namespace waam::twin::internal
