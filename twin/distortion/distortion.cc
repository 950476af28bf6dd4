// ComputeDistortion: mesh the deposit, run the chosen model, and interpolate its nodal displacements.
#include "twin/distortion/distortion.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "models/core/error.h"
#include "twin/distortion/hex_mesh.h"
#include "twin/distortion/inherent_strain.h"
#include "twin/scanner/point_hash.h"

namespace waam::twin {

void ValidateDistortionOptions(const DistortionOptions& o) {
  WAAM_THROW_UNLESS(o.element_mm > 0.0 && o.element_mm <= 50.0,
                    "distortion.element_mm = " << o.element_mm << ": must be in (0, 50] mm");
  WAAM_THROW_UNLESS(o.groups >= 1 && o.groups <= 1000, "distortion.groups = " << o.groups << ": must be in [1, 1000]");
}

DistortionField::DistortionField(double element_mm, std::unordered_map<std::uint64_t, Eigen::Vector3d> nodes,
                                 std::unordered_map<std::uint64_t, std::uint8_t> elements)
    : element_mm_(element_mm), nodes_(std::move(nodes)), elements_(std::move(elements)) {}

const Eigen::Vector3d* DistortionField::Node(int i, int j, int k) const {
  auto it = nodes_.find(CellKey(Eigen::Vector3i(i, j, k)));
  return it == nodes_.end() ? nullptr : &it->second;
}

Eigen::Vector3d DistortionField::Displacement(const Eigen::Vector3d& p_P) const {
  const Eigen::Vector3d s = p_P / element_mm_;
  const Eigen::Vector3i cell = CellOf(p_P, element_mm_);
  // The element containing the point, else the active element whose centre is nearest, within one cell and then
  // within two: a voxel of metal sticking out of the wall (a cell with too few voxels to be an element, next to
  // another such cell) must move with the wall, not stay behind as a speck at its undistorted place (part I after
  // compensation: a voxel 4.5 mm off the distorted surface).
  Eigen::Vector3i best = cell;
  if (!elements_.count(CellKey(cell))) {
    double best_d = std::numeric_limits<double>::infinity();
    for (int reach = 1; reach <= 2 && !std::isfinite(best_d); ++reach) {
      for (int dz = -reach; dz <= reach; ++dz) {
        for (int dy = -reach; dy <= reach; ++dy) {
          for (int dx = -reach; dx <= reach; ++dx) {
            const Eigen::Vector3i c = cell + Eigen::Vector3i(dx, dy, dz);
            if (!elements_.count(CellKey(c))) continue;
            const double d = (c.cast<double>() + Eigen::Vector3d::Constant(0.5) - s).squaredNorm();
            if (d < best_d) {
              best_d = d;
              best = c;
            }
          }
        }
      }
    }
    if (!std::isfinite(best_d)) return Eigen::Vector3d::Zero();
  }
  const Eigen::Vector3d t = (s - best.cast<double>()).cwiseMax(0.0).cwiseMin(1.0);
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (int n = 0; n < 8; ++n) {
    const int dx = n & 1, dy = (n >> 1) & 1, dz = (n >> 2) & 1;
    const Eigen::Vector3d* node = Node(best.x() + dx, best.y() + dy, best.z() + dz);
    if (node == nullptr) continue;
    const double w = (dx ? t.x() : 1 - t.x()) * (dy ? t.y() : 1 - t.y()) * (dz ? t.z() : 1 - t.z());
    u += w * *node;
  }
  return u;
}

namespace {

// The thermal law's factor per plan layer (empty without a thermal history).
std::vector<double> LayerStrainFactors(const DepositHistory& history, const models::DistortionParams& params,
                                       const DistortionOptions& options) {
  if (options.layer_heat.empty()) return {};
  WAAM_THROW_UNLESS(static_cast<int>(options.layer_heat.size()) >= history.layers(),
                    "distortion: the thermal history has " << options.layer_heat.size() << " layers, the build "
                                                           << history.layers() << ": one entry per layer is needed");
  WAAM_THROW_UNLESS(std::isfinite(params.reference_interpass_c),
                    "distortion model: reference_interpass_c is not given: the thermal law needs the interpass "
                    "temperature the strains were fitted at");
  std::vector<double> factors;
  factors.reserve(options.layer_heat.size());
  for (const LayerHeat& heat : options.layer_heat) {
    WAAM_THROW_UNLESS(std::isfinite(heat.interpass_c) && std::isfinite(heat.peak_c),
                      "distortion: a layer's interpass " << heat.interpass_c << " or peak " << heat.peak_c
                                                          << " degC is not a number");
    factors.push_back(params.ThermalFactor(heat.peak_c, heat.interpass_c));
  }
  return factors;
}

}  // namespace

DistortionField ComputeDistortion(const VoxelGrid& grid, const DepositHistory& history,
                                  const models::DistortionParams& params, const DistortionOptions& options,
                                  DistortionStats* stats) {
  ValidateDistortionOptions(options);
  models::ValidateDistortionParams(params, "distortion model");
  WAAM_THROW_UNLESS(grid.occupied() > 0, "distortion: the deposited part is empty");
  const auto start = std::chrono::steady_clock::now();
  const int factor = std::max(1, static_cast<int>(std::lround(options.element_mm / grid.voxel_mm())));
  const std::vector<double> layer_factor = LayerStrainFactors(history, params, options);
  const internal::HexMesh mesh = internal::BuildHexMesh(grid, history, params, factor, options.groups, layer_factor);
  WAAM_THROW_UNLESS(!mesh.elements.empty(),
                    "distortion.element_mm = " << options.element_mm << ": no element is half full of metal; the "
                    "part is thinner than two elements, use a smaller element_mm");
  DistortionStats local;
  DistortionStats& s = stats != nullptr ? *stats : local;
  s = DistortionStats{};
  s.elements = mesh.elements.size();
  s.nodes = mesh.node_ijk.size();
  const std::vector<Eigen::Vector3d> u = options.mode == models::DistortionMode::kReduced
                                             ? internal::SolveReduced(mesh, history, params)
                                             : internal::SolveInherentStrain(mesh, params, options, &s);
  std::unordered_map<std::uint64_t, Eigen::Vector3d> nodes;
  nodes.reserve(u.size());
  for (std::size_t n = 0; n < u.size(); ++n) {
    nodes.emplace(CellKey(mesh.node_ijk[n]), u[n]);
    s.max_displacement_mm = std::max(s.max_displacement_mm, u[n].norm());
  }
  std::unordered_map<std::uint64_t, std::uint8_t> elements;
  elements.reserve(mesh.elements.size());
  for (const internal::HexElement& e : mesh.elements) elements.emplace(CellKey(e.ijk), 1);
  s.solve_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return DistortionField(mesh.h_mm, std::move(nodes), std::move(elements));
}

}  // namespace waam::twin
