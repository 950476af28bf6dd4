// Torch-frame footprint columns: the lattice perpendicular to the torch axis and the walk of one column through the
// voxel slabs of the grid axis nearest the torch (a thick-line traversal in the spirit of Amanatides and Woo).
#include "twin/deposition/torch_columns.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"

namespace waam::twin::internal {
namespace {

// A torch this close to a grid axis (off-axis components below it) is taken as exactly on the axis, so planar
// paths deposit on the grid's own columns.
constexpr double kAxisSnap = 1e-9;

}  // namespace

TorchFrame::TorchFrame(const Eigen::Vector3d& tool_dir_P, double voxel_mm) : v_(voxel_mm) {
  WAAM_DEMAND(voxel_mm > 0.0 && tool_dir_P.norm() > 0.0);  // both checked where the scenario is read
  t_ = tool_dir_P.normalized();
  t_.cwiseAbs().maxCoeff(&axis_);
  a0_ = (axis_ + 1) % 3;
  a1_ = (axis_ + 2) % 3;
  if (std::abs(t_[a0_]) < kAxisSnap && std::abs(t_[a1_]) < kAxisSnap) {
    const double sign = t_[axis_] >= 0.0 ? 1.0 : -1.0;
    t_ = Eigen::Vector3d::Zero();
    t_[axis_] = sign;
    aligned_ = true;
  }
  // Lattice axes: the two other grid axes made perpendicular to t (Gram-Schmidt), so a grid-aligned torch gets the
  // grid's own columns and the lattice turns continuously with the torch.
  const Eigen::Vector3d g0 = Eigen::Vector3d::Unit(a0_);
  const Eigen::Vector3d g1 = Eigen::Vector3d::Unit(a1_);
  e1_ = (g0 - g0.dot(t_) * t_).normalized();
  e2_ = (g1 - g1.dot(t_) * t_ - g1.dot(e1_) * e1_).normalized();
  // A voxel centre of slab K in cell (i0, i1) is the point where the cell's axis line crosses the slab's mid plane
  // plus d = alpha e1 + beta e2 + gamma t with |alpha|, |beta| <= v/2 and d[axis] = 0, i.e.
  // gamma = -(alpha e1[axis] + beta e2[axis]) / t[axis]: this bounds d along a0, a1 and t.
  const double ta = t_[axis_];
  auto reach = [&](int a) {
    return 0.5 * v_ * (std::abs(e1_[a] - e1_[axis_] * t_[a] / ta) + std::abs(e2_[a] - e2_[axis_] * t_[a] / ta));
  };
  const double pad = 1e-9 * v_;
  reach0_ = reach(a0_) + pad;
  reach1_ = reach(a1_) + pad;
  rise_ = 0.5 * v_ * (std::abs(e1_[axis_]) + std::abs(e2_[axis_])) / std::abs(ta) + pad;
}

void TorchFrame::CollectColumn(int i0, int i1, double lo_mm, double hi_mm, std::vector<ColumnVoxel>* out) const {
  if (hi_mm < lo_mm) return;
  const double ta = t_[axis_];
  if (aligned_) {
    // The column is grid column (i0, i1); voxel K of it has its centre at height sign (K + 1/2) v.
    const double sign = ta > 0.0 ? 1.0 : -1.0;
    const int m_lo = static_cast<int>(std::ceil(lo_mm / v_ - 0.5));
    const int m_hi = static_cast<int>(std::floor(hi_mm / v_ - 0.5));
    if (m_hi < m_lo) return;
    const std::size_t first = out->size();
    out->resize(first + static_cast<std::size_t>(m_hi - m_lo + 1));
    ColumnVoxel* c = out->data() + first;
    for (int m = m_lo; m <= m_hi; ++m, ++c) {
      c->index[a0_] = i0;
      c->index[a1_] = i1;
      c->index[axis_] = sign > 0.0 ? m : -1 - m;
      c->height_mm = (m + 0.5) * v_;
    }
    return;
  }
  const Eigen::Vector3d p0 = (i0 + 0.5) * v_ * e1_ + (i1 + 0.5) * v_ * e2_;  // the cell's axis line: p0 + s t
  // Slabs whose crossing point lies within `rise` of the height range.
  const double k_a = ((lo_mm - rise_) * ta + p0[axis_]) / v_ - 0.5;
  const double k_b = ((hi_mm + rise_) * ta + p0[axis_]) / v_ - 0.5;
  const int k_lo = static_cast<int>(std::ceil(std::min(k_a, k_b)));
  const int k_hi = static_cast<int>(std::floor(std::max(k_a, k_b)));
  const std::size_t first = out->size();
  for (int k = k_lo; k <= k_hi; ++k) {
    const double s = ((k + 0.5) * v_ - p0[axis_]) / ta;
    const Eigen::Vector3d q = p0 + s * t_;
    const int j0_lo = static_cast<int>(std::ceil((q[a0_] - reach0_) / v_ - 0.5));
    const int j0_hi = static_cast<int>(std::floor((q[a0_] + reach0_) / v_ - 0.5));
    const int j1_lo = static_cast<int>(std::ceil((q[a1_] - reach1_) / v_ - 0.5));
    const int j1_hi = static_cast<int>(std::floor((q[a1_] + reach1_) / v_ - 0.5));
    for (int j0 = j0_lo; j0 <= j0_hi; ++j0) {
      for (int j1 = j1_lo; j1 <= j1_hi; ++j1) {
        ColumnVoxel c;
        c.index[axis_] = k;
        c.index[a0_] = j0;
        c.index[a1_] = j1;
        const Eigen::Vector3d centre = (c.index.cast<double>() + Eigen::Vector3d::Constant(0.5)) * v_;
        // The exact cell test: every voxel centre belongs to one cell only.
        if (static_cast<int>(std::floor(centre.dot(e1_) / v_)) != i0) continue;
        if (static_cast<int>(std::floor(centre.dot(e2_) / v_)) != i1) continue;
        c.height_mm = centre.dot(t_);
        if (c.height_mm < lo_mm || c.height_mm > hi_mm) continue;
        out->push_back(c);
      }
    }
  }
  std::sort(out->begin() + static_cast<std::ptrdiff_t>(first), out->end(),
            [](const ColumnVoxel& x, const ColumnVoxel& y) {
              if (x.height_mm != y.height_mm) return x.height_mm < y.height_mm;
              return std::lexicographical_compare(x.index.data(), x.index.data() + 3, y.index.data(),
                                                  y.index.data() + 3);
            });
}

}  // namespace waam::twin::internal
