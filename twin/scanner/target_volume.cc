// Target voxelization: ray parity per voxel column for meshes, polygon tests per column for layer regions.
#include "twin/scanner/target_volume.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/error.h"
#include "twin/scanner/surface_metrics.h"

namespace waam::twin {
namespace {

void CheckBoxSize(const Eigen::Vector3i& size, std::size_t max_voxels, const char* what) {
  const double n = static_cast<double>(size.x()) * size.y() * size.z();
  WAAM_THROW_UNLESS(n <= static_cast<double>(max_voxels),
                    what << ": the target box has " << n << " voxels, more than simulation.max_voxels = " << max_voxels
                         << "; use a coarser simulation.voxel_mm");
}

}  // namespace

TargetVolume::TargetVolume(double voxel_mm, const VoxelIndex& lo, const VoxelIndex& hi)
    : voxel_mm_(voxel_mm), lo_(lo), hi_(hi) {
  const Eigen::Vector3i n = size();
  if ((n.array() > 0).all()) inside_.assign(static_cast<std::size_t>(n.x()) * n.y() * n.z(), 0);
}

std::size_t TargetVolume::Offset(const VoxelIndex& v) const {
  const Eigen::Vector3i n = size();
  const Eigen::Vector3i d = v - lo_;
  return (static_cast<std::size_t>(d.z()) * n.y() + d.y()) * n.x() + d.x();
}

bool TargetVolume::Inside(const VoxelIndex& v) const {
  if ((v.array() < lo_.array()).any() || (v.array() > hi_.array()).any()) return false;
  return inside_[Offset(v)] != 0;
}

void TargetVolume::SetInside(const VoxelIndex& v, bool inside) {
  if ((v.array() < lo_.array()).any() || (v.array() > hi_.array()).any()) return;
  inside_[Offset(v)] = inside ? 1 : 0;
}

std::size_t TargetVolume::CountInside() const {
  return static_cast<std::size_t>(std::count(inside_.begin(), inside_.end(), std::uint8_t{1}));
}

TargetVolume TargetVolume::FromMesh(const planner::TriangleMesh& mesh, double v, std::size_t max_voxels) {
  WAAM_THROW_UNLESS(!mesh.vertices.empty() && !mesh.facets.empty(), "target volume: the mesh has no facets");
  Eigen::Vector3d bmin = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d bmax = -bmin;
  for (const Eigen::Vector3d& p : mesh.vertices) {
    bmin = bmin.cwiseMin(p);
    bmax = bmax.cwiseMax(p);
  }
  const VoxelIndex lo((bmin / v).array().floor().cast<int>());
  const VoxelIndex hi((bmax / v).array().floor().cast<int>());
  TargetVolume target(v, lo, hi);
  CheckBoxSize(target.size(), max_voxels, "target volume");
  const Eigen::Vector3i n = target.size();
  // Crossing heights of every column's centre ray with the facets.
  std::vector<std::vector<double>> crossings(static_cast<std::size_t>(n.x()) * n.y());
  for (const auto& f : mesh.facets) {
    const Eigen::Vector3d& a = mesh.vertices[f[0]];
    const Eigen::Vector3d& b = mesh.vertices[f[1]];
    const Eigen::Vector3d& c = mesh.vertices[f[2]];
    const double area2 = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(area2) < 1e-14) continue;  // vertical facet: no column crosses it
    const int i_lo = std::max(lo.x(), static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}) / v - 0.5)));
    const int i_hi = std::min(hi.x(), static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}) / v - 0.5)));
    const int j_lo = std::max(lo.y(), static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}) / v - 0.5)));
    const int j_hi = std::min(hi.y(), static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}) / v - 0.5)));
    for (int j = j_lo; j <= j_hi; ++j) {
      for (int i = i_lo; i <= i_hi; ++i) {
        // The ray is nudged off the column centre by an irrational fraction of a micrometre so that it never runs
        // exactly through a shared edge or vertex (which would count a crossing twice and break the parity).
        const double x = (i + 0.5) * v + 1.2345678e-6;
        const double y = (j + 0.5) * v + 2.7182818e-6;
        // Barycentric coordinates in the XY projection.
        const double w0 = ((b.x() - x) * (c.y() - y) - (c.x() - x) * (b.y() - y)) / area2;
        const double w1 = ((c.x() - x) * (a.y() - y) - (a.x() - x) * (c.y() - y)) / area2;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
        crossings[static_cast<std::size_t>(j - lo.y()) * n.x() + (i - lo.x())].push_back(w0 * a.z() + w1 * b.z() +
                                                                                           w2 * c.z());
      }
    }
  }
  for (int j = 0; j < n.y(); ++j) {
    for (int i = 0; i < n.x(); ++i) {
      std::vector<double>& zs = crossings[static_cast<std::size_t>(j) * n.x() + i];
      std::sort(zs.begin(), zs.end());
      for (std::size_t q = 0; q + 1 < zs.size(); q += 2) {
        for (int k = std::max(lo.z(), static_cast<int>(std::ceil(zs[q] / v - 0.5)));
             k <= std::min(hi.z(), static_cast<int>(std::floor(zs[q + 1] / v - 0.5))); ++k) {
          target.SetInside(VoxelIndex(lo.x() + i, lo.y() + j, k), true);
        }
      }
    }
  }
  return target;
}

TargetVolume TargetVolume::FromLayers(const planner::Plan& plan, double v, std::size_t max_voxels) {
  Eigen::Vector2d bmin = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d bmax = -bmin;
  double top = 0.0;
  for (const planner::LayerPath& layer : plan.layers) {
    top = std::max(top, layer.z_mm);
    for (const planner::PolygonWithHoles& r : layer.slice) {
      for (const Eigen::Vector2d& p : r.outer) {
        bmin = bmin.cwiseMin(p);
        bmax = bmax.cwiseMax(p);
      }
    }
  }
  WAAM_THROW_UNLESS(std::isfinite(bmin.x()), "target volume: the plan has no layer regions");
  const VoxelIndex lo(static_cast<int>(std::floor(bmin.x() / v)), static_cast<int>(std::floor(bmin.y() / v)), 0);
  const VoxelIndex hi(static_cast<int>(std::floor(bmax.x() / v)), static_cast<int>(std::floor(bmax.y() / v)),
                      std::max(0, static_cast<int>(std::ceil(top / v)) - 1));
  TargetVolume target(v, lo, hi);
  CheckBoxSize(target.size(), max_voxels, "target volume");
  double below = 0.0;
  for (const planner::LayerPath& layer : plan.layers) {
    const int k0 = std::max(0, static_cast<int>(std::ceil(below / v - 0.5)));
    const int k1 = std::min(hi.z(), static_cast<int>(std::floor(layer.z_mm / v - 0.5)));
    for (int j = lo.y(); j <= hi.y(); ++j) {
      for (int i = lo.x(); i <= hi.x(); ++i) {
        if (!InsideRegion(layer.slice, Eigen::Vector2d((i + 0.5) * v, (j + 0.5) * v))) continue;
        for (int k = k0; k <= k1; ++k) target.SetInside(VoxelIndex(i, j, k), true);
      }
    }
    below = std::max(below, layer.z_mm);
  }
  return target;
}

}  // namespace waam::twin
