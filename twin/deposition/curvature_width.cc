// Curvature widening of the bead along executed passes (Dai et al. 2020, CSW model, sec. 4 and Table 1).
#include "twin/deposition/curvature_width.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "models/core/error.h"

namespace waam::twin {
namespace {

// The pass point at arc length s (linear between the points).
Eigen::Vector3d PointAt(const ExecutedPass& pass, double s) {
  const std::vector<ExecutedPoint>& pts = pass.points;
  s = std::clamp(s, 0.0, pass.length_mm());
  const auto it = std::lower_bound(pts.begin(), pts.end(), s,
                                   [](const ExecutedPoint& p, double value) { return p.s_mm < value; });
  if (it == pts.begin()) return pts.front().p_P;
  if (it == pts.end()) return pts.back().p_P;
  const ExecutedPoint& b = *it;
  const ExecutedPoint& a = *(it - 1);
  const double span = b.s_mm - a.s_mm;
  const double t = span > 0.0 ? (s - a.s_mm) / span : 0.0;
  return a.p_P + t * (b.p_P - a.p_P);
}

}  // namespace

double PathRadiusAt(const ExecutedPass& pass, double s_mm, double window_mm) {
  WAAM_THROW_UNLESS(window_mm > 0.0, "path radius: window = " << window_mm << " mm: must be > 0");
  const double inf = std::numeric_limits<double>::infinity();
  if (pass.points.size() < 2) return inf;
  const Eigen::Vector3d a = PointAt(pass, s_mm - window_mm);
  const Eigen::Vector3d m = PointAt(pass, s_mm);
  const Eigen::Vector3d b = PointAt(pass, s_mm + window_mm);
  // Circumradius R = |ab| |am| |mb| / (4 area) = |ab| |am| |mb| / (2 |(m - a) x (b - a)|).
  const double twice_area = (m - a).cross(b - a).norm();
  const double sides = (b - a).norm() * (m - a).norm() * (b - m).norm();
  if (twice_area <= 1e-9 * std::max(sides, 1e-12)) return inf;
  return sides / (2.0 * twice_area);
}

void ApplyCurvatureWidth(const models::CswModel& csw, double min_radius_mm, ExecutedPass* pass) {
  WAAM_THROW_UNLESS(min_radius_mm > 0.0, "curvature width: minimum radius = " << min_radius_mm << " mm: must be > 0");
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<ExecutedPoint>& pts = pass->points;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    ExecutedPoint& p = pts[i];
    p.width_factor = 1.0;
    const double w = p.bead_width_mm;
    if (w <= 0.0 || p.speed_mm_s <= 0.0) continue;
    const double radius = models::CswModel::ApplicableRadius(PathRadiusAt(*pass, 0.5 * (pts[i - 1].s_mm + p.s_mm), w),
                                                             w, min_radius_mm);
    if (radius == inf) continue;  // straight, or a corner the sweep already shapes
    const double v = std::clamp(60.0 * p.speed_mm_s, csw.feasible().min_mm_per_min, csw.feasible().max_mm_per_min);
    const double straight = csw.Width(v, inf);
    if (straight <= 0.0) continue;
    p.width_factor = csw.Width(v, radius) / straight;
  }
}

}  // namespace waam::twin
