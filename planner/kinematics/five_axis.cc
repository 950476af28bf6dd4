// Dai et al. 2020 sec. 3: rotating a path point with its tool vector about a centre so that the vector points to a
// target direction, by two turntable axes (solution 1, Fig. 10) or through v_z as a transition (solution 2).
#include "planner/kinematics/five_axis.h"

#include <algorithm>
#include <cmath>

#include "models/core/numbers.h"

namespace waam::planner {
namespace {

Eigen::Matrix3d Rotation(const AxisAngles& g) {
  return (Eigen::AngleAxisd(g.a, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(g.b, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(g.c, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

// Angles (c about z, then a about x) that turn the unit vector v onto v_z = (0, 0, 1): turn v about z into the
// yOz plane on the +y side, then about x by acos(Z_v) (sec. 3.2, Fig. 12a).
AxisAngles ToVz(const Eigen::Vector3d& v) {
  AxisAngles g;
  const double horizontal = std::hypot(v.x(), v.y());
  // gamma = atan2(Y_v, X_v) is the azimuth; the turn that brings it onto +y is pi/2 - gamma. When v is vertical
  // any turn about z will do; 0 keeps the table still.
  g.c = horizontal < 1e-12 ? 0.0 : (kPi / 2) - std::atan2(v.y(), v.x());
  g.a = std::acos(std::clamp(v.z(), -1.0, 1.0));
  g.b = 0.0;
  return g;
}

}  // namespace

Eigen::Matrix4d DaiTransform(const Eigen::Vector3d& C_mm, const AxisAngles& angles) {
  // Eq. 3: M_st = M_oc * M_sot * M_co, translate C to O, rotate, translate back.
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  M.topLeftCorner<3, 3>() = Rotation(angles);
  M.topRightCorner<3, 1>() = C_mm - Rotation(angles) * C_mm;
  return M;
}

AxisAngles SolveDaiSolution1(const Eigen::Vector3d& v_s, const Eigen::Vector3d& v_t, bool positive_branch) {
  // Fig. 10a: turn v_s about z to Q, then Q about x to v_t. A turn about z keeps Z, a turn about x keeps X, so
  // Q = (X_t, +-sqrt(1 - X_t^2 - Z_s^2), Z_s). (The printed text writes Z_Q = Z_t and c from v_t's azimuth, which
  // does not keep Z across the z turn; the construction of Fig. 10 is the one implemented.)
  const Eigen::Vector3d s = v_s.normalized();
  const Eigen::Vector3d t = v_t.normalized();
  AxisAngles g;
  const double y2 = 1.0 - t.x() * t.x() - s.z() * s.z();
  if (y2 < -1e-12) {
    g.real = false;  // no real solution when X_t^2 + Z_s^2 > 1
    return g;
  }
  const double yq = (positive_branch ? 1.0 : -1.0) * std::sqrt(std::max(0.0, y2));
  const Eigen::Vector3d q(t.x(), yq, s.z());
  g.c = std::atan2(q.y(), q.x()) - std::atan2(s.y(), s.x());
  g.b = 0.0;
  g.a = std::atan2(t.z(), t.y()) - std::atan2(q.z(), q.y());
  return g;
}

Eigen::Matrix3d SolveDaiSolution2(const Eigen::Vector3d& v_s, const Eigen::Vector3d& v_t, AxisAngles* to_z) {
  // Eq. 4: M_soz turns v_s onto v_z; eq. 5: M_zot = M_toz^-1 turns v_z onto v_t (alpha' = -alpha_t,
  // gamma' = -gamma_t, applied in reverse order). M_sot = M_zot M_soz.
  const AxisAngles s = ToVz(v_s.normalized());
  const AxisAngles t = ToVz(v_t.normalized());
  if (to_z) *to_z = s;
  return Rotation(t).transpose() * Rotation(s);
}

}  // namespace waam::planner
