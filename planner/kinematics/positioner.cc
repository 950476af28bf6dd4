// Positioner angles from a build direction: closed form of the dissertation's eq. 5.13 with the target V = +z.
#include "planner/kinematics/positioner.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/numbers.h"
#include "planner/kinematics/angles.h"

namespace waam::planner {

Eigen::Isometry3d PartPose(const Positioner& positioner, double tilt, double rotation) {
  // eq. 5.9: R_xz = Rx(tilt) * Rz(rotation), with the axis offsets of the chain (eq. 5.1, 5.6).
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translate(positioner.p_BA);
  X.rotate(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()));
  X.translate(positioner.p_AC);
  X.rotate(Eigen::AngleAxisd(rotation, Eigen::Vector3d::UnitZ()));
  return X * positioner.X_CP;
}

PositionerAngles SolvePositionerAngles(const Positioner& positioner, const Eigen::Vector3d& build_dir_P,
                                       const PositionerAngles& previous) {
  // Build direction in the table frame C: m = R_CP n_P. We need Rx(t) Rz(r) m = z (eq. 5.10 with V = z, i.e.
  // a = b = 0, c = 1 in eq. 5.11-5.13). Then Rz(r) m = Rx(-t) z = (0, sin t, cos t): the tilt is fixed by
  // m_z = cos t (eq. 5.13, third line) and the rotation must bring the horizontal part of m onto +-y. With
  // a = 0, eq. B.1/B.5 reduce to tan(theta_z) = d / e, the same rotation. Lim & Soh's eq. 5-6 give the same pair
  // for a table with axes y-then-z; here the tilt axis is x as in the dissertation's FANUC positioner.
  // The first solution is also Dai et al. 2020's solution 2 (sec. 3.2, eq. 4) with v_t = v_z: gamma = atan2(Y, X),
  // alpha = acos(Z) (planner/kinematics/five_axis.cc; the two agree in tests/planner/five_axis_test.cc).
  const Eigen::Vector3d m = (positioner.X_CP.linear() * build_dir_P).normalized();
  const double horizontal = std::hypot(m.x(), m.y());
  PositionerAngles out;
  if (positioner.type != PositionerType::kTiltRotate) {
    // A turntable only turns the build direction about the vertical, which leaves its angle to vertical: the torch
    // follows the tool direction (tilted by the residual) and the table keeps its rotation. No positioner: nothing.
    out.rotation = positioner.type == PositionerType::kTurntable ? previous.rotation : 0.0;
    const Eigen::Vector3d turned = PartPose(positioner, 0.0, out.rotation).linear() * build_dir_P.normalized();
    out.residual_rad = std::acos(std::clamp(turned.z(), -1.0, 1.0));
    out.at_limit = out.residual_rad > 1e-6;
    return out;
  }
  if (horizontal < 1e-12) {
    out.tilt = m.z() > 0.0 ? 0.0 : kPi;  // upside down needs a half turn of the tilt axis
    out.rotation = previous.rotation;
  } else {
    const double t = std::acos(std::clamp(m.z(), -1.0, 1.0));  // > 0
    const double phi = std::atan2(m.y(), m.x());
    // Two solutions: (t, pi/2 - phi) and (-t, -pi/2 - phi).
    double best_cost = std::numeric_limits<double>::infinity();
    for (int s = 0; s < 2; ++s) {
      const double tilt = s ? -t : t;
      const double rot = NearestAngleCopy((s ? -(kPi / 2) : (kPi / 2)) - phi, positioner.rotation_lower,
                                     positioner.rotation_upper, previous.rotation);
      const double tilt_clamped = std::clamp(tilt, positioner.tilt_lower, positioner.tilt_upper);
      const bool rot_inside = rot >= positioner.rotation_lower && rot <= positioner.rotation_upper;
      const double cost = 1e3 * std::abs(tilt - tilt_clamped) + (rot_inside ? 0.0 : 1e6) +
                          std::abs(tilt_clamped - previous.tilt) + 0.5 * std::abs(rot - previous.rotation);
      if (cost < best_cost) {
        best_cost = cost;
        out.tilt = tilt;
        out.rotation = rot;
      }
    }
  }
  const double clamped = std::clamp(out.tilt, positioner.tilt_lower, positioner.tilt_upper);
  if (clamped != out.tilt) {
    out.at_limit = true;
    out.tilt = clamped;
  }
  // What is left of the build direction's tilt from vertical after the positioner turned it (eq. 5.17).
  const Eigen::Vector3d turned = PartPose(positioner, out.tilt, out.rotation).linear() * build_dir_P.normalized();
  out.residual_rad = std::acos(std::clamp(turned.z(), -1.0, 1.0));
  return out;
}

PositionerAngles SolvePositionerAnglesWithin(const Positioner& positioner, const Eigen::Vector3d& build_dir_P,
                                             const PositionerAngles& previous, double tolerance_rad) {
  if (tolerance_rad <= 0.0) return SolvePositionerAngles(positioner, build_dir_P, previous);
  // Build direction in the table frame: m. After the table turns by r it is m' = Rz(r) m, whose x part
  // m'_x = h cos(r + phi) no tilt about x can remove; the tilt t = atan2(m'_y, m'_z) brings the rest up. The torch
  // angle left is asin(|m'_x|), within the tolerance while |cos(r + phi)| <= sin(tol) / h.
  const Eigen::Vector3d m = (positioner.X_CP.linear() * build_dir_P).normalized();
  const double h = std::hypot(m.x(), m.y());
  const double phi = std::atan2(m.y(), m.x());
  double r = previous.rotation;
  const double limit = std::sin(tolerance_rad);
  if (h > limit) {
    const double alpha = std::acos(limit / h);  // allowed: r + phi in [alpha, pi - alpha] (mod pi)
    const double x = r + phi;
    const double xm = x - kPi * std::floor(x / kPi);  // in [0, pi)
    if (xm < alpha) {
      r += (alpha - xm <= xm + alpha) ? alpha - xm : -(xm + alpha);
    } else if (xm > kPi - alpha) {
      r += (xm - (kPi - alpha) <= (kPi + alpha) - xm) ? -(xm - (kPi - alpha)) : (kPi + alpha) - xm;
    }
  }
  const Eigen::Vector3d turned = Eigen::AngleAxisd(r, Eigen::Vector3d::UnitZ()) * m;
  const double t = std::atan2(turned.y(), turned.z());
  if (r < positioner.rotation_lower || r > positioner.rotation_upper || t < positioner.tilt_lower ||
      t > positioner.tilt_upper) {
    return SolvePositionerAngles(positioner, build_dir_P, previous);
  }
  PositionerAngles out;
  out.tilt = t;
  out.rotation = r;
  const Eigen::Vector3d up = PartPose(positioner, out.tilt, out.rotation).linear() * build_dir_P.normalized();
  out.residual_rad = std::acos(std::clamp(up.z(), -1.0, 1.0));
  return out;
}

}  // namespace waam::planner
