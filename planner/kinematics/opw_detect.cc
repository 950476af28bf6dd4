// OPW parameters, offsets and sign corrections read off an arm's joint axes at its zero pose (any vendor convention).
#include <cmath>
#include <sstream>

#include "planner/kinematics/opw_arm.h"

namespace waam::planner {
namespace {

constexpr double kDetectParallel = 1e-9;  // |cos| or |sin| tolerance of axis directions
constexpr double kDetectMeetMm = 1e-6;    // axes closer than this meet, mm

Eigen::Matrix3d DetectRy(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }
Eigen::Matrix3d DetectRz(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

double DetectWrapPi(double a) { return std::remainder(a, 2.0 * kPi); }

// Closest points of two lines p + s u and q + t v; false when they are parallel.
bool DetectClosestPoints(const Eigen::Vector3d& p, const Eigen::Vector3d& u, const Eigen::Vector3d& q,
                   const Eigen::Vector3d& v, Eigen::Vector3d* on_u, Eigen::Vector3d* on_v) {
  const double b = u.dot(v);
  const double den = 1.0 - b * b;
  if (den < kDetectParallel) return false;
  const Eigen::Vector3d w = p - q;
  const double s = (b * v.dot(w) - u.dot(w)) / den;
  const double t = (v.dot(w) - b * u.dot(w)) / den;
  *on_u = p + s * u;
  *on_v = q + t * v;
  return true;
}

double DetectDistanceToLine(const Eigen::Vector3d& x, const Eigen::Vector3d& p, const Eigen::Vector3d& u) {
  const Eigen::Vector3d d = x - p;
  return (d - d.dot(u) * u).norm();
}

}  // namespace

std::optional<OpwArm> OpwFromAxes(const ArmAxes& axes, std::string* why) {
  auto fail = [&](const std::string& reason) -> std::optional<OpwArm> {
    if (why) *why = reason;
    return std::nullopt;
  };
  std::array<Eigen::Vector3d, 6> A;
  for (int j = 0; j < 6; ++j) A[j] = axes.axis_R[j].normalized();
  const std::array<Eigen::Vector3d, 6>& P = axes.point_R;

  // j1 along +-z of R, through its origin.
  if (std::abs(A[0].z()) < 1.0 - kDetectParallel) return fail("j1 is not along z of the arm base");
  if (std::hypot(P[0].x(), P[0].y()) > kDetectMeetMm) return fail("j1 does not pass through the arm base origin");
  const int s1 = A[0].z() > 0.0 ? 1 : -1;
  // j2 horizontal, j3 parallel to it.
  if (std::abs(A[1].z()) > kDetectParallel) return fail("j2 is not orthogonal to j1");
  if (std::abs(A[1].dot(A[2])) < 1.0 - kDetectParallel) return fail("j3 is not parallel to j2");

  // The arm plane at the zero pose: e_y along j2, e_x forward, turned by theta about z; a1 >= 0 picks the side.
  double theta = std::atan2(-A[1].x(), A[1].y());
  Eigen::Vector3d e_x(std::cos(theta), std::sin(theta), 0.0);
  if (P[1].dot(e_x) < -kDetectMeetMm) {
    theta = DetectWrapPi(theta + kPi);
    e_x = -e_x;
  }
  const Eigen::Vector3d e_z = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d e_y = e_z.cross(e_x);
  const int s2 = A[1].dot(e_y) > 0.0 ? 1 : -1;
  const int s3 = A[2].dot(e_y) > 0.0 ? 1 : -1;

  OpwArm arm;
  arm.a1 = P[1].dot(e_x);
  arm.c1 = P[1].z();
  // Upper arm: from the j2 axis to the j3 axis in the plane, at theta2 from vertical.
  const double dx = P[2].dot(e_x) - arm.a1;
  const double dz = P[2].z() - arm.c1;
  arm.c2 = std::hypot(dx, dz);
  if (arm.c2 < kDetectMeetMm) return fail("j2 and j3 coincide");
  const double theta2 = std::atan2(dx, dz);

  // Wrist centre: j4 and j5 meet there, and j6 passes through it.
  Eigen::Vector3d c4_point, c5_point;
  if (!DetectClosestPoints(P[3], A[3], P[4], A[4], &c4_point, &c5_point)) return fail("j4 and j5 are parallel");
  if ((c4_point - c5_point).norm() > kDetectMeetMm) return fail("j4 and j5 do not meet (no spherical wrist)");
  const Eigen::Vector3d C = 0.5 * (c4_point + c5_point);
  if (DetectDistanceToLine(C, P[5], A[5]) > kDetectMeetMm) return fail("j6 does not pass through the wrist centre");
  if (std::abs(A[3].dot(e_y)) > kDetectParallel) return fail("j4 does not lie in the arm plane");
  arm.b = C.dot(e_y);

  // Forearm: z_c along j4, pointing from j3 towards the wrist centre (c3 > 0).
  Eigen::Vector3d z_c = A[3];
  double phi0 = std::atan2(z_c.dot(e_x), z_c.dot(e_z));
  Eigen::Vector3d x_c = std::cos(phi0) * e_x - std::sin(phi0) * e_z;
  const Eigen::Vector3d v = C - P[2];
  if (v.dot(z_c) < 0.0) {
    z_c = -z_c;
    x_c = -x_c;
    phi0 = DetectWrapPi(phi0 + kPi);
  }
  arm.c3 = v.dot(z_c);
  arm.a2 = v.dot(x_c);
  const int s4 = A[3].dot(z_c) > 0.0 ? 1 : -1;

  // j5 about y of the wrist frame turned by alpha0 about the forearm.
  Eigen::Matrix3d R_c;
  R_c << x_c, e_y, z_c;
  const Eigen::Vector3d a5 = R_c.transpose() * A[4];
  if (std::abs(a5.z()) > kDetectParallel) return fail("j5 is not orthogonal to j4");
  double alpha0 = std::atan2(-a5.x(), a5.y());
  int s5 = 1;
  if (alpha0 > kPi / 2 + 1e-12) alpha0 -= kPi, s5 = -1;
  if (alpha0 < -kPi / 2 - 1e-12) alpha0 += kPi, s5 = -1;

  // j6 along z of the end frame, turned by beta0 about j5; the flange lies c4 along it.
  const Eigen::Matrix3d R_c4 = R_c * DetectRz(alpha0);
  const Eigen::Vector3d a6 = R_c4.transpose() * A[5];
  if (std::abs(a6.y()) > kDetectParallel) return fail("j6 is not orthogonal to j5");
  double beta0 = std::atan2(a6.x(), a6.z());
  Eigen::Vector3d dir = R_c4 * Eigen::Vector3d(std::sin(beta0), 0.0, std::cos(beta0));
  const Eigen::Vector3d to_flange = axes.X_RF0.translation() - C;
  if (to_flange.dot(dir) < -kDetectMeetMm) {
    beta0 = DetectWrapPi(beta0 + kPi);
    dir = -dir;
  }
  arm.c4 = to_flange.dot(dir);
  if ((to_flange - arm.c4 * dir).norm() > kDetectMeetMm) return fail("the flange is not on the j6 axis");
  const int s6 = A[5].dot(dir) > 0.0 ? 1 : -1;

  // OPW joints t = s q - offset: at q = 0 they are (theta, theta2, phi0 - theta2, alpha0, beta0, 0).
  arm.sign_corrections = {s1, s2, s3, s4, s5, s6};
  arm.offsets = {-theta, -theta2, -DetectWrapPi(phi0 - theta2), -alpha0, -beta0, 0.0};
  arm.R_EF = (R_c4 * DetectRy(beta0)).transpose() * axes.X_RF0.linear();
  // The model must give back the zero pose it was read from.
  const Eigen::Isometry3d X0 = ForwardKinematics(arm, Joints6::Zero());
  if ((X0.translation() - axes.X_RF0.translation()).norm() > 1e-6 ||
      (X0.linear() - axes.X_RF0.linear()).norm() > 1e-9) {
    return fail("the OPW model read from the axes does not reproduce the zero pose");
  }
  return arm;
}

}  // namespace waam::planner
