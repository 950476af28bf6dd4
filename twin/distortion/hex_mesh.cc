// The coarse hexahedral mesh of the deposited part: voxels binned into elements, layer and heat input averaged.
#include "twin/distortion/hex_mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <queue>

#include "twin/distortion/distortion.h"
#include "twin/scanner/point_hash.h"

namespace waam::twin::internal {
namespace {

int FloorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

struct Accum {
  int count = 0;
  double layer = 0.0;
  double strain = 0.0;
  Eigen::Vector3d dir = Eigen::Vector3d::Zero();
  std::size_t order = 0;  // first insertion, for a deterministic element order
};

}  // namespace

HexMesh BuildHexMesh(const VoxelGrid& grid, const DepositHistory& history, const models::DistortionParams& params,
                     int factor, int groups, const std::vector<double>& layer_factor) {
  HexMesh mesh;
  mesh.h_mm = factor * grid.voxel_mm();
  std::unordered_map<std::uint64_t, Accum> bins;
  std::vector<std::uint64_t> order;
  const std::vector<VoxelDeposit>& deposits = history.Voxels(grid);
  std::size_t n = 0;
  grid.ForEach([&](const VoxelIndex& v, const VoxelData&) {
    const int I = FloorDiv(v.x(), factor), J = FloorDiv(v.y(), factor), K = FloorDiv(v.z(), factor);
    const std::uint64_t key = CellKey(Eigen::Vector3i(I, J, K));
    auto [it, inserted] = bins.try_emplace(key);
    if (inserted) {
      it->second.order = order.size();
      order.push_back(key);
    }
    Accum& a = it->second;
    const VoxelDeposit& deposit = deposits[n++];
    const int layer = deposit.layer;
    const double q = params.HeatInput(history.wire_feed_mm_s(), deposit.speed_mm_s);
    a.count += 1;
    a.layer += layer;
    a.strain += layer_factor.empty() ? params.StrainAt(q) : params.StrainAt(q) * layer_factor[layer];
    a.dir += history.LayerDir(layer);
  });
  const int full = factor * factor * factor;
  int max_layer = 0;
  for (int l = 0; l < history.layers(); ++l) max_layer = l;
  mesh.groups = std::max(1, groups);
  auto node = [&](int I, int J, int K) {
    const std::uint64_t key = CellKey(Eigen::Vector3i(I, J, K));
    auto [it, inserted] = mesh.node_id.try_emplace(key, static_cast<int>(mesh.node_ijk.size()));
    if (inserted) mesh.node_ijk.emplace_back(I, J, K);
    return it->second;
  };
  for (std::uint64_t key : order) {
    const Accum& a = bins[key];
    if (2 * a.count < full) continue;
    HexElement e;
    e.ijk = CellOfKey(key);
    e.layer = a.layer / a.count;
    e.strain = a.strain / a.count;
    e.dir = a.dir.norm() > 0 ? Eigen::Vector3d(a.dir.normalized()) : Eigen::Vector3d::UnitZ();
    e.center = (e.ijk.cast<double>() + Eigen::Vector3d::Constant(0.5)) * mesh.h_mm;
    e.group = max_layer > 0 ? std::min(mesh.groups - 1, static_cast<int>(e.layer * mesh.groups / (max_layer + 1)))
                            : 0;
    for (int n = 0; n < 8; ++n) {
      const int dx = n & 1, dy = (n >> 1) & 1, dz = (n >> 2) & 1;
      e.nodes[n] = node(e.ijk.x() + dx, e.ijk.y() + dy, e.ijk.z() + dz);
    }
    mesh.elements.push_back(e);
  }
  return mesh;
}

std::size_t KeepConnectedToSubstrate(const HexMesh& mesh, std::vector<std::uint8_t>* active) {
  std::vector<std::vector<int>> node_elements(mesh.node_ijk.size());
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    if (!(*active)[e]) continue;
    for (int n : mesh.elements[e].nodes) node_elements[n].push_back(static_cast<int>(e));
  }
  std::vector<std::uint8_t> reached(mesh.elements.size(), 0);
  std::queue<int> queue;
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    if ((*active)[e] && mesh.elements[e].ijk.z() == 0) {
      reached[e] = 1;
      queue.push(static_cast<int>(e));
    }
  }
  while (!queue.empty()) {
    const int e = queue.front();
    queue.pop();
    for (int n : mesh.elements[e].nodes) {
      for (int f : node_elements[n]) {
        if (!reached[f]) {
          reached[f] = 1;
          queue.push(f);
        }
      }
    }
  }
  std::size_t cleared = 0;
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    if ((*active)[e] && !reached[e]) {
      (*active)[e] = 0;
      ++cleared;
    }
  }
  return cleared;
}

}  // namespace waam::twin::internal
