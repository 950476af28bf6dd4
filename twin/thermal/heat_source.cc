// Goldak's double-ellipsoid heat source integrated over boxes and grid cells.
#include "twin/thermal/heat_source.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "models/core/error.h"

namespace waam::twin {
namespace {

const double kSqrt3 = std::sqrt(3.0);
constexpr double kSupportSemiAxes = 1.5;  // the support box's reach, semi-axes (erfc(1.5 sqrt 3) = 2.4e-4 outside)
constexpr int kObliqueColumns = 4;        // footprint columns per cell side for an oblique travel

// Share of the half-Gaussian exp(-3 u^2 / c^2) on u >= 0 that lies in [lo, hi] (its integral on [0, inf) is 1).
double HalfLine(double lo, double hi, double c) {
  return std::erf(kSqrt3 * std::max(0.0, hi) / c) - std::erf(kSqrt3 * std::max(0.0, lo) / c);
}

// Share along the travel, both lobes: the front- (x >= 0, c_f, f_f) and rear-quadrant (x < 0, c_r, f_r) densities
// of Goldak et al. 1984's double ellipsoid (docs/THERMAL.md eqs. (5)-(6); the paper's own equation numbers are not
// cited: no copy of it could be checked). A lobe integrates to f Q / 2 over its quarter of space (6 sqrt(3) f Q / (a b c pi sqrt(pi)) times the
// Gaussian integral a b c pi sqrt(pi) / (12 sqrt(3))), so with f_f + f_r = 2 the source holds exactly Q.
double AlongShare(const DoubleEllipsoid& s, double lo, double hi) {
  const double sum = s.front_mm + s.rear_mm;
  const double f_front = 2.0 * s.front_mm / sum, f_rear = 2.0 * s.rear_mm / sum;
  return 0.5 * f_front * HalfLine(lo, hi, s.front_mm) + 0.5 * f_rear * HalfLine(-hi, -lo, s.rear_mm);
}

// Density along the travel per mm (integrates to 1 over the line).
double AlongDensity(const DoubleEllipsoid& s, double x) {
  const double sum = s.front_mm + s.rear_mm;
  const double c = x >= 0.0 ? s.front_mm : s.rear_mm;
  // 0.5 f (2 sqrt 3 / (c sqrt pi)) exp(-3 x^2 / c^2) with f = 2 c / sum.
  return 2.0 * kSqrt3 / (sum * std::sqrt(std::numbers::pi)) * std::exp(-3.0 * x * x / (c * c));
}

double AcrossShare(const DoubleEllipsoid& s, double lo, double hi) {
  return 0.5 * (std::erf(kSqrt3 * hi / s.half_width_mm) - std::erf(kSqrt3 * lo / s.half_width_mm));
}

double AcrossDensity(const DoubleEllipsoid& s, double y) {
  const double a = s.half_width_mm;
  return kSqrt3 / (a * std::sqrt(std::numbers::pi)) * std::exp(-3.0 * y * y / (a * a));
}

// Depth share of [z_lo, z_hi] (z up, the surface at 0; the heat lies below it).
double DownShare(const DoubleEllipsoid& s, double z_lo, double z_hi) { return HalfLine(-z_hi, -z_lo, s.depth_mm); }

// The standing arc's pool: the moving pool's front lobe on both sides.
DoubleEllipsoid Standing(DoubleEllipsoid s) {
  s.rear_mm = s.front_mm;
  return s;
}

}  // namespace

void CheckDoubleEllipsoid(const DoubleEllipsoid& s) {
  const auto check = [](double v, const char* name) {
    WAAM_THROW_UNLESS(std::isfinite(v) && v > 0.0, "double ellipsoid " << name << " = " << v << ": must be > 0");
  };
  check(s.half_width_mm, "half_width_mm");
  check(s.depth_mm, "depth_mm");
  check(s.front_mm, "front_mm");
  check(s.rear_mm, "rear_mm");
}

double DoubleEllipsoidShare(const DoubleEllipsoid& s, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  if ((hi.array() <= lo.array()).any()) return 0.0;
  return AlongShare(s, lo.x(), hi.x()) * AcrossShare(s, lo.y(), hi.y()) * DownShare(s, lo.z(), hi.z());
}

double DoubleEllipsoidCellShare(const DoubleEllipsoid& source, const Eigen::Vector3d& arc_mm,
                                const Eigen::Vector2d& travel, const Eigen::AlignedBox3d& cell_mm) {
  const double length = travel.norm();
  const DoubleEllipsoid s = length > 0.0 ? source : Standing(source);
  const Eigen::Vector2d d = length > 0.0 ? Eigen::Vector2d(travel / length) : Eigen::Vector2d::UnitX();
  const Eigen::Vector3d lo = cell_mm.min() - arc_mm, hi = cell_mm.max() - arc_mm;
  const double down = DownShare(s, lo.z(), hi.z());
  if (down <= 0.0) return 0.0;
  constexpr double kAligned = 1e-9;
  if (std::abs(d.y()) < kAligned || std::abs(d.x()) < kAligned) {
    // The cell is a box of the source's frame: x' = d . p, y' = n . p with n = (-d.y, d.x).
    const bool along_x = std::abs(d.y()) < kAligned;
    const double sign_x = along_x ? (d.x() > 0 ? 1.0 : -1.0) : (d.y() > 0 ? 1.0 : -1.0);
    const double a0 = along_x ? lo.x() : lo.y(), a1 = along_x ? hi.x() : hi.y();
    const double b0 = along_x ? lo.y() : lo.x(), b1 = along_x ? hi.y() : hi.x();
    // Across: n . p is +y for travel along +x, -x for travel along +y (and flips with the sign).
    const double sign_y = along_x ? sign_x : -sign_x;
    const double x0 = sign_x > 0 ? a0 : -a1, x1 = sign_x > 0 ? a1 : -a0;
    const double y0 = sign_y > 0 ? b0 : -b1, y1 = sign_y > 0 ? b1 : -b0;
    return AlongShare(s, x0, x1) * AcrossShare(s, y0, y1) * down;
  }
  // An oblique travel: the footprint on columns, each column's share its density at its centre times its area.
  const Eigen::Vector2d n(-d.y(), d.x());
  const double wx = (hi.x() - lo.x()) / kObliqueColumns, wy = (hi.y() - lo.y()) / kObliqueColumns;
  double footprint = 0.0;
  for (int i = 0; i < kObliqueColumns; ++i) {
    for (int j = 0; j < kObliqueColumns; ++j) {
      const Eigen::Vector2d p(lo.x() + (i + 0.5) * wx, lo.y() + (j + 0.5) * wy);
      footprint += AlongDensity(s, d.dot(p)) * AcrossDensity(s, n.dot(p));
    }
  }
  return footprint * wx * wy * down;
}

Eigen::AlignedBox3d DoubleEllipsoidSupport(const DoubleEllipsoid& source, const Eigen::Vector3d& arc_mm,
                                           const Eigen::Vector2d& travel) {
  const double length = travel.norm();
  const DoubleEllipsoid s = length > 0.0 ? source : Standing(source);
  const Eigen::Vector2d d = length > 0.0 ? Eigen::Vector2d(travel / length) : Eigen::Vector2d::UnitX();
  const Eigen::Vector2d n(-d.y(), d.x());
  const double k = kSupportSemiAxes;
  Eigen::AlignedBox3d box;
  for (double along : {k * s.front_mm, -k * s.rear_mm}) {
    for (double across : {k * s.half_width_mm, -k * s.half_width_mm}) {
      const Eigen::Vector2d p = arc_mm.head<2>() + along * d + across * n;
      box.extend(Eigen::Vector3d(p.x(), p.y(), arc_mm.z()));
      box.extend(Eigen::Vector3d(p.x(), p.y(), arc_mm.z() - k * s.depth_mm));
    }
  }
  return box;
}

}  // namespace waam::twin
