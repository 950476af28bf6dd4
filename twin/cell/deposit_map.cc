// Height map of the deposited part: beads rasterised as flat-topped strips, the nozzle tested as a row of spheres.
#include "twin/cell/deposit_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace waam::twin {
namespace {
constexpr float kEmpty = -1e9f;
}  // namespace

DepositMap::DepositMap(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy, double cell_mm)
    : origin_(min_xy), cell_(cell_mm), top_(kEmpty) {
  nx_ = std::max(1, static_cast<int>(std::ceil((max_xy.x() - min_xy.x()) / cell_)) + 1);
  ny_ = std::max(1, static_cast<int>(std::ceil((max_xy.y() - min_xy.y()) / cell_)) + 1);
  height_.assign(static_cast<std::size_t>(nx_) * ny_, kEmpty);
}

void DepositMap::Deposit(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double width_mm) {
  const double half = 0.5 * width_mm;
  const Eigen::Vector2d a2 = a.head<2>(), b2 = b.head<2>();
  const Eigen::Vector2d lo = a2.cwiseMin(b2).array() - half, hi = a2.cwiseMax(b2).array() + half;
  const int x0 = std::max(0, static_cast<int>(std::floor((lo.x() - origin_.x()) / cell_)));
  const int x1 = std::min(nx_ - 1, static_cast<int>(std::ceil((hi.x() - origin_.x()) / cell_)));
  const int y0 = std::max(0, static_cast<int>(std::floor((lo.y() - origin_.y()) / cell_)));
  const int y1 = std::min(ny_ - 1, static_cast<int>(std::ceil((hi.y() - origin_.y()) / cell_)));
  const Eigen::Vector2d ab = b2 - a2;
  const double len2 = ab.squaredNorm();
  // Per cell centre c: the nearest point of the segment, a2 + t ab, within half the width (squared distances).
  const double half2 = half * half;
  for (int iy = y0; iy <= y1; ++iy) {
    const double cy = origin_.y() + cell_ * iy;
    for (int ix = x0; ix <= x1; ++ix) {
      const double cx = origin_.x() + cell_ * ix;
      const double t =
          len2 > 0.0 ? std::clamp(((cx - a2.x()) * ab.x() + (cy - a2.y()) * ab.y()) / len2, 0.0, 1.0) : 0.0;
      const double ex = a2.x() + t * ab.x() - cx, ey = a2.y() + t * ab.y() - cy;
      if (ex * ex + ey * ey > half2) continue;
      const float z = static_cast<float>(a.z() + t * (b.z() - a.z()));
      float& h = height_[Index(ix, iy)];
      h = std::max(h, z);
      top_ = std::max(top_, static_cast<double>(z));
    }
  }
}

double DepositMap::Penetration(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius_mm) const {
  const double r = radius_mm;
  // Nothing deposited as high as the capsule's lowest point: no contact (the usual case, checked first).
  if (std::min(a.z(), b.z()) - r > top_) return 0.0;
  const double length = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(length / (0.5 * r))));
  double deepest = 0.0;
  for (int k = 0; k <= n; ++k) {
    const Eigen::Vector3d c = a + (b - a) * (static_cast<double>(k) / n);
    if (c.z() - r > top_) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor((c.x() - r - origin_.x()) / cell_)));
    const int x1 = std::min(nx_ - 1, static_cast<int>(std::ceil((c.x() + r - origin_.x()) / cell_)));
    const int y0 = std::max(0, static_cast<int>(std::floor((c.y() - r - origin_.y()) / cell_)));
    const int y1 = std::min(ny_ - 1, static_cast<int>(std::ceil((c.y() + r - origin_.y()) / cell_)));
    for (int iy = y0; iy <= y1; ++iy) {
      for (int ix = x0; ix <= x1; ++ix) {
        const float h = height_[Index(ix, iy)];
        if (h == kEmpty) continue;
        const Eigen::Vector2d p = origin_ + cell_ * Eigen::Vector2d(ix, iy);
        const double d2 = (p - c.head<2>()).squaredNorm();
        if (d2 >= r * r) continue;
        // Lowest point of the sphere above this cell, against the metal's top there.
        deepest = std::max(deepest, h - (c.z() - std::sqrt(r * r - d2)));
      }
    }
  }
  return deepest;
}

}  // namespace waam::twin
