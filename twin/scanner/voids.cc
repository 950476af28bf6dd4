// Void finding: per horizontal cut, a flood fill of the air from outside the part; what the air cannot reach inside
// the target is enclosed. Enclosed voxels are grouped in 3D and split into capped voids and open valleys.
#include "twin/scanner/voids.h"

#include <algorithm>
#include <cmath>
#include <deque>

#include <Eigen/Eigenvalues>

#include "models/core/error.h"
#include "models/core/progress.h"

namespace waam::twin {
namespace {

EmptyRegion Describe(const std::vector<VoxelIndex>& cells, double v) {
  EmptyRegion region;
  region.voxels = cells.size();
  region.volume_mm3 = static_cast<double>(cells.size()) * v * v * v;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const VoxelIndex& c : cells) mean += (c.cast<double>() + Eigen::Vector3d::Constant(0.5)) * v;
  mean /= static_cast<double>(cells.size());
  region.centroid_mm = mean;
  // Length as a caliper on a milled section measures it: the extent along the principal axis in the XY plane.
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const VoxelIndex& c : cells) {
    const Eigen::Vector2d d = (c.head<2>().cast<double>() + Eigen::Vector2d::Constant(0.5)) * v - mean.head<2>();
    cov += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Eigen::Vector2d axis = eig.eigenvectors().col(1);
  double lo = 1e300, hi = -1e300;
  for (const VoxelIndex& c : cells) {
    const double t = ((c.head<2>().cast<double>() + Eigen::Vector2d::Constant(0.5)) * v).dot(axis);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  region.length_mm = hi - lo + v;
  return region;
}

// Flood-fills the air of horizontal cut kz from the border of the padded box (origin lo, nx x ny) through empty
// voxels, 4-connected; reached[j * nx + i] = 1 where the outside air gets.
void FloodCut(const VoxelGrid& grid, const VoxelIndex& lo, int nx, int ny, int kz, std::vector<std::uint8_t>* reached) {
  reached->assign(static_cast<std::size_t>(nx) * ny, 0);
  std::deque<std::pair<int, int>> queue;
  for (int i = 0; i < nx; ++i) {
    for (int j : {0, ny - 1}) queue.emplace_back(i, j);
  }
  for (int j = 1; j + 1 < ny; ++j) {
    for (int i : {0, nx - 1}) queue.emplace_back(i, j);
  }
  while (!queue.empty()) {
    const auto [i, j] = queue.front();
    queue.pop_front();
    if (i < 0 || j < 0 || i >= nx || j >= ny) continue;
    std::uint8_t& r = (*reached)[static_cast<std::size_t>(j) * nx + i];
    if (r || grid.Occupied(VoxelIndex(lo.x() + i, lo.y() + j, kz))) continue;
    r = 1;
    queue.emplace_back(i + 1, j);
    queue.emplace_back(i - 1, j);
    queue.emplace_back(i, j + 1);
    queue.emplace_back(i, j - 1);
  }
}

}  // namespace

std::vector<EmptyRegion> SectionVoids(const VoxelGrid& grid, const TargetVolume& target, double z_mm) {
  const double v = grid.voxel_mm();
  WAAM_THROW_UNLESS(std::abs(target.voxel_mm() - v) < 1e-12,
                    "voids: target voxel " << target.voxel_mm() << " mm differs from the grid's " << v << " mm");
  std::vector<EmptyRegion> regions;
  const Eigen::Vector3i n = target.size();
  if ((n.array() <= 0).any()) return regions;
  const VoxelIndex lo = target.lo() - VoxelIndex(1, 1, 0);
  const int nx = n.x() + 2;
  const int ny = n.y() + 2;
  const int kz = static_cast<int>(std::floor(z_mm / v));
  std::vector<std::uint8_t> reached;
  FloodCut(grid, lo, nx, ny, kz, &reached);
  // 4-connected regions of the enclosed cells of this cut.
  std::vector<VoxelIndex> cells;
  std::vector<std::pair<int, int>> stack;
  for (int j = 1; j + 1 < ny; ++j) {
    for (int i = 1; i + 1 < nx; ++i) {
      auto enclosed = [&](int a, int b) {
        const VoxelIndex vox(lo.x() + a, lo.y() + b, kz);
        return !reached[static_cast<std::size_t>(b) * nx + a] && !grid.Occupied(vox) && target.Inside(vox);
      };
      if (!enclosed(i, j)) continue;
      cells.clear();
      stack.assign(1, {i, j});
      reached[static_cast<std::size_t>(j) * nx + i] = 2;
      while (!stack.empty()) {
        const auto [a, b] = stack.back();
        stack.pop_back();
        cells.emplace_back(lo.x() + a, lo.y() + b, kz);
        for (const auto& [da, db] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
          const int qa = a + da, qb = b + db;
          if (qa < 1 || qb < 1 || qa + 1 >= nx || qb + 1 >= ny || !enclosed(qa, qb)) continue;
          reached[static_cast<std::size_t>(qb) * nx + qa] = 2;
          stack.emplace_back(qa, qb);
        }
      }
      regions.push_back(Describe(cells, v));
    }
  }
  std::sort(regions.begin(), regions.end(),
            [](const EmptyRegion& a, const EmptyRegion& b) { return a.length_mm > b.length_mm; });
  return regions;
}

namespace {

// The target's box padded with one ring of air in x and y: origin lo, nx x ny x nz voxels.
struct PaddedBox {
  VoxelIndex lo;
  int nx = 0, ny = 0, nz = 0;
  std::size_t At(int i, int j, int k) const { return (static_cast<std::size_t>(k) * ny + j) * nx + i; }
  std::size_t Column(int i, int j) const { return static_cast<std::size_t>(j) * nx + i; }
};

// Per voxel of `box`, 1 where no outside air reaches it in its horizontal cut, it is empty and inside the target
// (`enclosed`); per column, the highest occupied k in box coordinates, -1 for none, counting metal up to 64 voxels
// above the box, which still caps a void (`column_top`).
void MarkEnclosed(const VoxelGrid& grid, const TargetVolume& target, const PaddedBox& box,
                  std::vector<std::uint8_t>* enclosed, std::vector<int>* column_top) {
  const VoxelIndex& lo = box.lo;
  enclosed->assign(static_cast<std::size_t>(box.nx) * box.ny * box.nz, 0);
  column_top->assign(static_cast<std::size_t>(box.nx) * box.ny, -1);
  std::vector<std::uint8_t> reached;
  for (int k = 0; k < box.nz; ++k) {
    const int kz = lo.z() + k;
    if (kz < 0) continue;  // substrate
    CheckInterrupt();
    FloodCut(grid, lo, box.nx, box.ny, kz, &reached);
    for (int j = 1; j + 1 < box.ny; ++j) {
      for (int i = 1; i + 1 < box.nx; ++i) {
        const VoxelIndex vox(lo.x() + i, lo.y() + j, kz);
        if (grid.Occupied(vox)) {
          (*column_top)[box.Column(i, j)] = k;
          continue;
        }
        if (!reached[box.Column(i, j)] && target.Inside(vox)) (*enclosed)[box.At(i, j, k)] = 1;
      }
    }
  }
  for (int j = 1; j + 1 < box.ny; ++j) {
    for (int i = 1; i + 1 < box.nx; ++i) {
      for (int kz = lo.z() + box.nz; kz < lo.z() + box.nz + 64; ++kz) {
        if (grid.Occupied(VoxelIndex(lo.x() + i, lo.y() + j, kz))) (*column_top)[box.Column(i, j)] = kz - lo.z();
      }
    }
  }
}

// The 6-connected region of enclosed voxels from (i, j, k), marked 2 in `enclosed` as it is taken, into `cells`;
// true when it is open (a voxel of it has no metal above it).
bool TakeRegion(const PaddedBox& box, const std::vector<int>& column_top, int i, int j, int k,
                std::vector<std::uint8_t>* enclosed, std::vector<VoxelIndex>* cells) {
  cells->clear();
  bool open = false;
  std::vector<Eigen::Vector3i> stack(1, Eigen::Vector3i(i, j, k));
  (*enclosed)[box.At(i, j, k)] = 2;
  while (!stack.empty()) {
    const Eigen::Vector3i c = stack.back();
    stack.pop_back();
    cells->push_back(box.lo + c);
    open = open || column_top[box.Column(c.x(), c.y())] < c.z();
    for (const Eigen::Vector3i& d : {Eigen::Vector3i(1, 0, 0), Eigen::Vector3i(-1, 0, 0), Eigen::Vector3i(0, 1, 0),
                                    Eigen::Vector3i(0, -1, 0), Eigen::Vector3i(0, 0, 1), Eigen::Vector3i(0, 0, -1)}) {
      const Eigen::Vector3i q = c + d;
      if (q.x() < 0 || q.y() < 0 || q.z() < 0 || q.x() >= box.nx || q.y() >= box.ny || q.z() >= box.nz) continue;
      if ((*enclosed)[box.At(q.x(), q.y(), q.z())] != 1) continue;
      (*enclosed)[box.At(q.x(), q.y(), q.z())] = 2;
      stack.push_back(q);
    }
  }
  return open;
}

// Sorts regions by volume, largest first, and adds up their volume and longest length.
void SortRegions(std::vector<EmptyRegion>& regions, double* volume, double* max_length) {
  std::sort(regions.begin(), regions.end(),
            [](const EmptyRegion& a, const EmptyRegion& b) { return a.volume_mm3 > b.volume_mm3; });
  for (const EmptyRegion& r : regions) {
    *volume += r.volume_mm3;
    *max_length = std::max(*max_length, r.length_mm);
  }
}

}  // namespace

VoidReport FindVoids(const VoxelGrid& grid, const TargetVolume& target, double min_volume_mm3) {
  const double v = grid.voxel_mm();
  WAAM_THROW_UNLESS(std::abs(target.voxel_mm() - v) < 1e-12,
                    "voids: target voxel " << target.voxel_mm() << " mm differs from the grid's " << v << " mm");
  VoidReport report;
  report.min_volume_mm3 = min_volume_mm3;
  const Eigen::Vector3i n = target.size();
  if ((n.array() <= 0).any()) return report;
  const PaddedBox box{target.lo() - VoxelIndex(1, 1, 0), n.x() + 2, n.y() + 2, n.z()};
  std::vector<std::uint8_t> enclosed;
  std::vector<int> column_top;
  MarkEnclosed(grid, target, box, &enclosed, &column_top);
  // 6-connected regions of enclosed voxels: capped voids, open valleys, or too small to count.
  std::vector<VoxelIndex> cells;
  for (int k = 0; k < box.nz; ++k) {
    for (int j = 0; j < box.ny; ++j) {
      for (int i = 0; i < box.nx; ++i) {
        if (enclosed[box.At(i, j, k)] != 1) continue;
        const bool open = TakeRegion(box, column_top, i, j, k, &enclosed, &cells);
        const EmptyRegion region = Describe(cells, v);
        if (region.volume_mm3 < min_volume_mm3) {
          ++report.small_regions;
          report.small_volume_mm3 += region.volume_mm3;
          continue;
        }
        (open ? report.valleys : report.voids).push_back(region);
      }
    }
  }
  SortRegions(report.voids, &report.void_volume_mm3, &report.void_max_length_mm);
  SortRegions(report.valleys, &report.valley_volume_mm3, &report.valley_max_length_mm);
  return report;
}

}  // namespace waam::twin
