// Height map of the deposited part: beads rasterised as flat-topped strips (lazily, when a query reaches below the
// top), the nozzle tested as a row of spheres, distances as lower bounds from the grid's columns.
#include "twin/cell/deposit_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace waam::twin {
namespace {
constexpr float kEmpty = -1e9f;
constexpr int kTile = 8;  // grid points per side of a tile of tile_top_

// Squared distance from p to the 2D segment a-b.
double SegmentDistance2(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).squaredNorm();
}
}  // namespace

DepositMap::DepositMap(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy, double cell_mm)
    : origin_(min_xy), cell_(cell_mm), top_(kEmpty) {
  nx_ = std::max(1, static_cast<int>(std::ceil((max_xy.x() - min_xy.x()) / cell_)) + 1);
  ny_ = std::max(1, static_cast<int>(std::ceil((max_xy.y() - min_xy.y()) / cell_)) + 1);
  height_.assign(static_cast<std::size_t>(nx_) * ny_, kEmpty);
  tiles_x_ = (nx_ + kTile - 1) / kTile;
  tile_top_.assign(static_cast<std::size_t>(tiles_x_) * ((ny_ + kTile - 1) / kTile), kEmpty);
}

float DepositMap::TileTop(int x0, int x1, int y0, int y1) const {
  float top = kEmpty;
  for (int ty = y0 / kTile; ty <= y1 / kTile; ++ty) {
    for (int tx = x0 / kTile; tx <= x1 / kTile; ++tx) top = std::max(top, tile_top_[ty * tiles_x_ + tx]);
  }
  return top;
}

void DepositMap::Deposit(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double width_mm) {
  pending_.push_back({a, b, width_mm});
  // The strip's heights interpolate a.z and b.z: none is above the higher end.
  top_ = std::max(top_, std::max(a.z(), b.z()));
}

void DepositMap::Flush() const {
  for (const Bead& bead : pending_) Rasterise(bead);
  pending_.clear();
}

void DepositMap::Rasterise(const Bead& bead) const {
  const Eigen::Vector3d& a = bead.a;
  const Eigen::Vector3d& b = bead.b;
  const double half = 0.5 * bead.width_mm;
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
      float& tile = tile_top_[(iy / kTile) * tiles_x_ + ix / kTile];
      tile = std::max(tile, z);
    }
  }
}

double DepositMap::Penetration(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius_mm) const {
  const double r = radius_mm;
  // Nothing deposited as high as the capsule's lowest point: no contact (the usual case, checked first).
  if (std::min(a.z(), b.z()) - r > top_) return 0.0;
  Flush();
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
    if (x0 > x1 || y0 > y1) continue;
    // A clearance bound first: no metal under this sphere's square reaches its lowest point (a cell's metal h
    // reaches into the sphere only if h > c.z - sqrt(r^2 - d^2) >= c.z - r), so its cells need not be visited.
    if (TileTop(x0, x1, y0, y1) <= c.z() - r) continue;
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

double DepositMap::Distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius_mm,
                            double cap_mm) const {
  const double r = radius_mm;
  const double z_low = std::min(a.z(), b.z());
  // Every column ends at or below top_: the capsule's lowest point above it bounds the distance.
  const double above = z_low - r - top_;
  if (above >= cap_mm) return cap_mm;
  Flush();
  // Columns whose grid point lies farther than cap + r from the axis's xy projection are at least cap away; each
  // column within is at least sqrt(e^2 + max(0, z_low - h)^2) - r away (e: its xy distance from the axis), as
  // every point of the axis is e away in xy and no lower than z_low.
  const double reach = cap_mm + r;
  const Eigen::Vector2d a2 = a.head<2>(), b2 = b.head<2>();
  const Eigen::Vector2d lo = a2.cwiseMin(b2).array() - reach, hi = a2.cwiseMax(b2).array() + reach;
  const int x0 = std::max(0, static_cast<int>(std::floor((lo.x() - origin_.x()) / cell_)));
  const int x1 = std::min(nx_ - 1, static_cast<int>(std::ceil((hi.x() - origin_.x()) / cell_)));
  const int y0 = std::max(0, static_cast<int>(std::floor((lo.y() - origin_.y()) / cell_)));
  const int y1 = std::min(ny_ - 1, static_cast<int>(std::ceil((hi.y() - origin_.y()) / cell_)));
  double best2 = reach * reach;  // squared distance from the axis to the nearest column found
  for (int iy = y0; iy <= y1; ++iy) {
    for (int ix = x0; ix <= x1; ++ix) {
      const float h = height_[Index(ix, iy)];
      if (h == kEmpty) continue;
      const double v = std::max(0.0, z_low - h);
      if (v * v >= best2) continue;
      const Eigen::Vector2d p = origin_ + cell_ * Eigen::Vector2d(ix, iy);
      best2 = std::min(best2, SegmentDistance2(p, a2, b2) + v * v);
    }
  }
  return std::max({0.0, above, std::min(cap_mm, std::sqrt(best2) - r)});
}

}  // namespace waam::twin
