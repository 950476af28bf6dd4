// OPW forward and inverse kinematics: shoulder x elbow x wrist = 8 closed-form branches.
#include "planner/kinematics/opw_arm.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/numbers.h"
#include "planner/kinematics/angles.h"

namespace waam::planner {
namespace {

constexpr double kWristSingularSin = 1e-9;  // |sin j5| below this: j4 and j6 are coupled

double Deg(double d) { return d * kPi / 180.0; }

Eigen::Matrix3d Rx(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix(); }
Eigen::Matrix3d Ry(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }
Eigen::Matrix3d Rz(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

}  // namespace

OpwArm OpwArm::ArcMate100iC12() {
  // Geometry: OPW parameters of the FANUC M-10iA (the ARC Mate 100iC/12 is its arc-welding version), from
  // ROS-Industrial fanuc_m10ia_support/config/opw_parameters_m10ia.yaml: a1 = 150, a2 = -200, b = 0, c1 = 450,
  // c2 = 600, c3 = 640, c4 = 100 mm; joint frames as in fanuc_m10ia_support/urdf/m10ia_macro.xacro.
  // Reach = a1 + c3 + c4 + ... : the wrist centre reaches a1 + c2 + hypot(a2, c3) = 1420.5 mm from the j1 axis,
  // matching the 1420 mm of the dissertation's Table 2.
  // Limits: J1 +-170 deg (340 deg data-sheet range); J2 -90..160, J3 -180..264, J4 +-190, J5 +-190, J6 +-360 deg
  // (the URDF's limits, serial j3 convention). Speeds 210, 190, 210, 400, 400, 600 deg/s (data sheet = URDF).
  OpwArm arm;
  arm.name = "FANUC ARC Mate 100iC/12";
  arm.a1 = 150.0;
  arm.a2 = -200.0;
  arm.c1 = 450.0;
  arm.c2 = 600.0;
  arm.c3 = 640.0;
  arm.c4 = 100.0;
  arm.lower << Deg(-170), Deg(-90), Deg(-180), Deg(-190), Deg(-190), Deg(-360);
  arm.upper << Deg(170), Deg(160), Deg(264), Deg(190), Deg(190), Deg(360);
  arm.max_speed << Deg(210), Deg(190), Deg(210), Deg(400), Deg(400), Deg(600);
  return arm;
}

Eigen::Vector3d WristCentre(const OpwArm& arm, const Joints6& q) {
  // R -> j2 axis -> j3 axis -> wrist centre, with the forearm rotated by j2 - j3 about +y.
  const Eigen::Matrix3d R1 = Rz(q[0]);
  const Eigen::Vector3d p2 = R1 * Eigen::Vector3d(arm.a1, 0.0, arm.c1);
  const Eigen::Vector3d p3 = p2 + R1 * Ry(q[1]) * Eigen::Vector3d(0.0, 0.0, arm.c2);
  return p3 + R1 * Ry(q[1] - q[2]) * Eigen::Vector3d(arm.c3, 0.0, -arm.a2);
}

Eigen::Isometry3d ForwardKinematics(const OpwArm& arm, const Joints6& q) {
  const Eigen::Matrix3d R03 = Rz(q[0]) * Ry(q[1] - q[2]);
  const Eigen::Matrix3d R06 = R03 * Rx(-q[3]) * Ry(-q[4]) * Rx(-q[5]);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R06;
  X.translation() = WristCentre(arm, q) + R06 * Eigen::Vector3d(arm.c4, 0.0, 0.0);
  return X;
}

IkSolutions SolveIk(const OpwArm& arm, const Eigen::Isometry3d& X_RF, const Joints6* seed) {
  IkSolutions out;
  const Eigen::Matrix3d& R = X_RF.linear();
  // Wrist centre: back from the flange along its normal (x of F) by c4.
  const Eigen::Vector3d w = X_RF.translation() - arm.c4 * R.col(0);
  const double rho = std::hypot(w.x(), w.y());
  const double h = w.z() - arm.c1;
  // Forearm as one rigid vector from j3 to the wrist centre: length k, angle alpha0 from the upper arm at j3 = 0.
  const double k = std::hypot(arm.c3, arm.a2);
  const double alpha0 = std::atan2(arm.c3, -arm.a2);
  const double seed_q1 = seed ? (*seed)[0] : 0.0;
  const double seed_q4 = seed ? (*seed)[3] : 0.0;

  double best_excess = std::numeric_limits<double>::infinity();
  for (int shoulder = 0; shoulder < 2; ++shoulder) {
    // Shoulder: j1 towards the wrist centre (front) or away from it (back, reaching over).
    double q1;
    if (rho < 1e-9) {
      q1 = seed_q1 + (shoulder ? kPi : 0.0);  // shoulder singularity: j1 is free
    } else {
      q1 = std::atan2(w.y(), w.x()) + (shoulder ? kPi : 0.0);
    }
    const double r = (shoulder ? -rho : rho) - arm.a1;  // horizontal distance j2 -> wrist centre in the arm plane
    const double s2 = r * r + h * h;
    // Law of cosines in the triangle j2 - j3 - wrist centre: cos(alpha0 - q3) = D.
    double D = (s2 - arm.c2 * arm.c2 - k * k) / (2.0 * arm.c2 * k);
    if (std::abs(D) > 1.0) {
      const double s = std::sqrt(s2);
      const double excess = D > 1.0 ? s - (arm.c2 + k) : std::abs(arm.c2 - k) - s;
      if (excess > 1e-9) {
        best_excess = std::min(best_excess, excess);
        continue;
      }
      D = std::clamp(D, -1.0, 1.0);
    }
    const double gamma = std::atan2(r, h);  // direction of the wrist centre from j2, from vertical towards +x
    for (int elbow = 0; elbow < 2; ++elbow) {
      const double beta = (elbow ? -1.0 : 1.0) * std::acos(D);  // angle of the forearm vector from the upper arm
      const double q3 = alpha0 - beta;
      const double q2 = gamma - std::atan2(k * std::sin(beta), arm.c2 + k * std::cos(beta));
      // Wrist: R36 = Rx(-q4) Ry(-q5) Rx(-q6) = Rx(a) Ry(b) Rx(c), an X-Y-X Euler decomposition.
      const Eigen::Matrix3d M = (Rz(q1) * Ry(q2 - q3)).transpose() * R;
      const double sb_abs = std::hypot(M(0, 1), M(0, 2));
      for (int flip = 0; flip < 2; ++flip) {
        double a, b, c;
        if (sb_abs < kWristSingularSin) {
          // j5 = 0 (or pi): only q4 + q6 (or q6 - q4) is defined; j4 keeps the seed.
          a = -seed_q4;
          if (M(0, 0) > 0.0) {
            b = 0.0;
            c = std::atan2(M(2, 1), M(1, 1)) - a;
          } else {
            b = kPi;
            c = std::atan2(-M(2, 1), M(1, 1)) + a;
          }
          if (flip) continue;  // both wrist branches coincide
        } else {
          const double sgn = flip ? 1.0 : -1.0;  // flip = j5 > 0 = b < 0
          b = std::atan2(-sgn * sb_abs, M(0, 0));
          a = std::atan2(-sgn * M(1, 0), sgn * M(2, 0));
          c = std::atan2(-sgn * M(0, 1), -sgn * M(0, 2));
        }
        IkSolution& sol = out.solutions[out.count++];
        sol.q << q1, q2, q3, -a, -b, -c;
        sol.branch = shoulder | (elbow << 1) | (flip << 2);
        sol.within_limits = true;
        for (int j = 0; j < 6; ++j) {
          const double target = seed ? (*seed)[j] : 0.0;
          sol.q[j] = NearestAngleCopy(sol.q[j], arm.lower[j], arm.upper[j], target);
          if (sol.q[j] < arm.lower[j] || sol.q[j] > arm.upper[j]) sol.within_limits = false;
        }
      }
    }
  }
  if (out.count == 0) out.reach_excess_mm = best_excess;
  return out;
}

int PickNearest(const OpwArm& arm, const IkSolutions& solutions, const Joints6* seed) {
  static const double kWeight[6] = {1.0, 1.0, 1.0, 0.5, 0.5, 0.5};
  int best = -1;
  double best_cost = std::numeric_limits<double>::infinity();
  for (int i = 0; i < solutions.count; ++i) {
    const IkSolution& s = solutions.solutions[i];
    double cost = 0.0;
    if (!s.within_limits) {
      int joint = 0;
      cost += 1e6 * (1.0 - LimitMargin(arm, s.q, &joint));
    }
    for (int j = 0; j < 6; ++j) {
      const double d = seed ? s.q[j] - (*seed)[j] : s.q[j];
      cost += kWeight[j] * d * d;
    }
    if (cost < best_cost) {
      best_cost = cost;
      best = i;
    }
  }
  return best;
}

double LimitMargin(const OpwArm& arm, const Joints6& q, int* joint) {
  double margin = std::numeric_limits<double>::infinity();
  for (int j = 0; j < 6; ++j) {
    const double m = std::min(q[j] - arm.lower[j], arm.upper[j] - q[j]);
    if (m < margin) {
      margin = m;
      if (joint) *joint = j;
    }
  }
  return margin;
}

}  // namespace waam::planner
