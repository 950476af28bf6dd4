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

// The arm's axes and what is read off them, stage by stage (each stage reads what the ones before it found).
struct Detection {
  std::array<Eigen::Vector3d, 6> A;  // unit axis directions in R
  std::array<Eigen::Vector3d, 6> P;  // a point on each axis in R, mm
  std::array<int, 6> s{};            // sign corrections
  double theta = 0.0;                // the arm plane's turn about z at the zero pose, rad
  Eigen::Vector3d e_x, e_y, e_z;     // the arm plane: e_x forward, e_y along j2
  double theta2 = 0.0;               // upper arm from vertical, rad
  Eigen::Vector3d C;                 // wrist centre, mm
  Eigen::Vector3d z_c, x_c;          // forearm frame: z_c along j4 towards the wrist centre
  double phi0 = 0.0;                 // forearm angle, rad
  double alpha0 = 0.0, beta0 = 0.0;  // j5 and j6 turns, rad
  Eigen::Matrix3d R_c4;              // wrist frame turned by alpha0 about the forearm
};

// j1 along +-z of R through its origin, j2 horizontal, j3 parallel to it; the arm plane at the zero pose: e_y along
// j2, e_x forward, turned by theta about z (a1 >= 0 picks the side). Returns why not, or nullptr.
const char* DetectArmPlane(Detection* d) {
  const auto& A = d->A;
  const auto& P = d->P;
  if (std::abs(A[0].z()) < 1.0 - kDetectParallel) return "j1 is not along z of the arm base";
  if (std::hypot(P[0].x(), P[0].y()) > kDetectMeetMm) return "j1 does not pass through the arm base origin";
  d->s[0] = A[0].z() > 0.0 ? 1 : -1;
  if (std::abs(A[1].z()) > kDetectParallel) return "j2 is not orthogonal to j1";
  if (std::abs(A[1].dot(A[2])) < 1.0 - kDetectParallel) return "j3 is not parallel to j2";
  d->theta = std::atan2(-A[1].x(), A[1].y());
  d->e_x = Eigen::Vector3d(std::cos(d->theta), std::sin(d->theta), 0.0);
  if (P[1].dot(d->e_x) < -kDetectMeetMm) {
    d->theta = DetectWrapPi(d->theta + kPi);
    d->e_x = -d->e_x;
  }
  d->e_z = Eigen::Vector3d::UnitZ();
  d->e_y = d->e_z.cross(d->e_x);
  d->s[1] = A[1].dot(d->e_y) > 0.0 ? 1 : -1;
  d->s[2] = A[2].dot(d->e_y) > 0.0 ? 1 : -1;
  return nullptr;
}

// Shoulder and upper arm: a1, c1, and c2 from the j2 axis to the j3 axis in the plane, at theta2 from vertical.
const char* DetectUpperArm(Detection* d, OpwArm* arm) {
  const auto& P = d->P;
  arm->a1 = P[1].dot(d->e_x);
  arm->c1 = P[1].z();
  const double dx = P[2].dot(d->e_x) - arm->a1;
  const double dz = P[2].z() - arm->c1;
  arm->c2 = std::hypot(dx, dz);
  if (arm->c2 < kDetectMeetMm) return "j2 and j3 coincide";
  d->theta2 = std::atan2(dx, dz);
  return nullptr;
}

// Wrist centre: j4 and j5 meet there, and j6 passes through it; b is its offset across the arm plane.
const char* DetectWristCentre(Detection* d, OpwArm* arm) {
  const auto& A = d->A;
  const auto& P = d->P;
  Eigen::Vector3d c4_point, c5_point;
  if (!DetectClosestPoints(P[3], A[3], P[4], A[4], &c4_point, &c5_point)) return "j4 and j5 are parallel";
  if ((c4_point - c5_point).norm() > kDetectMeetMm) return "j4 and j5 do not meet (no spherical wrist)";
  d->C = 0.5 * (c4_point + c5_point);
  if (DetectDistanceToLine(d->C, P[5], A[5]) > kDetectMeetMm) return "j6 does not pass through the wrist centre";
  if (std::abs(A[3].dot(d->e_y)) > kDetectParallel) return "j4 does not lie in the arm plane";
  arm->b = d->C.dot(d->e_y);
  return nullptr;
}

// Forearm: z_c along j4, pointing from j3 towards the wrist centre (c3 > 0); a2 across it.
void DetectForearm(Detection* d, OpwArm* arm) {
  d->z_c = d->A[3];
  d->phi0 = std::atan2(d->z_c.dot(d->e_x), d->z_c.dot(d->e_z));
  d->x_c = std::cos(d->phi0) * d->e_x - std::sin(d->phi0) * d->e_z;
  const Eigen::Vector3d v = d->C - d->P[2];
  if (v.dot(d->z_c) < 0.0) {
    d->z_c = -d->z_c;
    d->x_c = -d->x_c;
    d->phi0 = DetectWrapPi(d->phi0 + kPi);
  }
  arm->c3 = v.dot(d->z_c);
  arm->a2 = v.dot(d->x_c);
  d->s[3] = d->A[3].dot(d->z_c) > 0.0 ? 1 : -1;
}

// j5 about y of the wrist frame turned by alpha0 about the forearm; j6 along z of the end frame, turned by beta0
// about j5; the flange (at X_RF0) lies c4 along it.
const char* DetectWrist(Detection* d, const Eigen::Isometry3d& X_RF0, OpwArm* arm) {
  Eigen::Matrix3d R_c;
  R_c << d->x_c, d->e_y, d->z_c;
  const Eigen::Vector3d a5 = R_c.transpose() * d->A[4];
  if (std::abs(a5.z()) > kDetectParallel) return "j5 is not orthogonal to j4";
  d->alpha0 = std::atan2(-a5.x(), a5.y());
  d->s[4] = 1;
  if (d->alpha0 > kPi / 2 + 1e-12) d->alpha0 -= kPi, d->s[4] = -1;
  if (d->alpha0 < -kPi / 2 - 1e-12) d->alpha0 += kPi, d->s[4] = -1;

  d->R_c4 = R_c * DetectRz(d->alpha0);
  const Eigen::Vector3d a6 = d->R_c4.transpose() * d->A[5];
  if (std::abs(a6.y()) > kDetectParallel) return "j6 is not orthogonal to j5";
  d->beta0 = std::atan2(a6.x(), a6.z());
  Eigen::Vector3d dir = d->R_c4 * Eigen::Vector3d(std::sin(d->beta0), 0.0, std::cos(d->beta0));
  const Eigen::Vector3d to_flange = X_RF0.translation() - d->C;
  if (to_flange.dot(dir) < -kDetectMeetMm) {
    d->beta0 = DetectWrapPi(d->beta0 + kPi);
    dir = -dir;
  }
  arm->c4 = to_flange.dot(dir);
  if ((to_flange - arm->c4 * dir).norm() > kDetectMeetMm) return "the flange is not on the j6 axis";
  d->s[5] = d->A[5].dot(dir) > 0.0 ? 1 : -1;
  return nullptr;
}

}  // namespace

std::optional<OpwArm> OpwFromAxes(const ArmAxes& axes, std::string* why) {
  auto fail = [&](const std::string& reason) -> std::optional<OpwArm> {
    if (why) *why = reason;
    return std::nullopt;
  };
  Detection d;
  for (int j = 0; j < 6; ++j) d.A[j] = axes.axis_R[j].normalized();
  d.P = axes.point_R;
  OpwArm arm;
  const char* failure = DetectArmPlane(&d);
  if (!failure) failure = DetectUpperArm(&d, &arm);
  if (!failure) failure = DetectWristCentre(&d, &arm);
  if (!failure) DetectForearm(&d, &arm);
  if (!failure) failure = DetectWrist(&d, axes.X_RF0, &arm);
  if (failure) return fail(failure);

  // OPW joints t = s q - offset: at q = 0 they are (theta, theta2, phi0 - theta2, alpha0, beta0, 0).
  arm.sign_corrections = d.s;
  arm.offsets = {-d.theta, -d.theta2, -DetectWrapPi(d.phi0 - d.theta2), -d.alpha0, -d.beta0, 0.0};
  arm.R_EF = (d.R_c4 * DetectRy(d.beta0)).transpose() * axes.X_RF0.linear();
  // The model must give back the zero pose it was read from.
  const Eigen::Isometry3d X0 = ForwardKinematics(arm, Joints6::Zero());
  if ((X0.translation() - axes.X_RF0.translation()).norm() > 1e-6 ||
      (X0.linear() - axes.X_RF0.linear()).norm() > 1e-9) {
    return fail("the OPW model read from the axes does not reproduce the zero pose");
  }
  return arm;
}

}  // namespace waam::planner
