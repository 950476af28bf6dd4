// OPW forward and inverse kinematics (Brandstoetter, Angerer, Hofbaur 2014): shoulder x elbow x wrist = 8 closed-form
// branches, in the OPW model's own joints, mapped to the vendor's by offsets and sign corrections.
#include "planner/kinematics/opw_arm.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "models/core/numbers.h"
#include "planner/kinematics/angles.h"

namespace waam::planner {
namespace {

constexpr double kWristSingularSin = 1e-9;  // |sin j5| below this: j4 and j6 are coupled
constexpr double kWeight[6] = {1.0, 1.0, 1.0, 0.5, 0.5, 0.5};  // PickNearest's joint weights: wrist joints count half

double Deg(double d) { return d * kPi / 180.0; }

Eigen::Matrix3d Ry(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }
Eigen::Matrix3d Rz(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

// The OPW model's joints for the arm's joints q.
Joints6 ToOpw(const OpwArm& arm, const Joints6& q) {
  Joints6 t;
  for (int j = 0; j < 6; ++j) t[j] = arm.sign_corrections[j] * q[j] - arm.offsets[j];
  return t;
}

// Orientation of the OPW end frame E for OPW joints t (paper eq. for R_0c * R_ce: Rz Ry(t2 + t3) * Rz Ry Rz).
Eigen::Matrix3d EndRotation(const Joints6& t) {
  return Rz(t[0]) * Ry(t[1] + t[2]) * Rz(t[3]) * Ry(t[4]) * Rz(t[5]);
}

}  // namespace

OpwArm OpwArm::FromParameters(std::string name, double a1, double a2, double b, double c1, double c2, double c3,
                              double c4, const std::array<double, 6>& offsets,
                              const std::array<int, 6>& sign_corrections, const Eigen::Matrix3d& R_RF0) {
  OpwArm arm;
  arm.name = std::move(name);
  arm.a1 = a1;
  arm.a2 = a2;
  arm.b = b;
  arm.c1 = c1;
  arm.c2 = c2;
  arm.c3 = c3;
  arm.c4 = c4;
  arm.offsets = offsets;
  arm.sign_corrections = sign_corrections;
  arm.R_EF = EndRotation(ToOpw(arm, Joints6::Zero())).transpose() * R_RF0;
  return arm;
}

OpwArm OpwArm::ArcMate100iC12() {
  // Geometry: OPW parameters of the FANUC M-10iA (the ARC Mate 100iC/12 is its arc-welding version), from
  // ROS-Industrial fanuc_m10ia_support/config/opw_parameters_m10ia.yaml: a1 = 0.15, a2 = -0.20, b = 0, c1 = 0.45,
  // c2 = 0.60, c3 = 0.64, c4 = 0.10 m, offsets [0, 0, -pi/2, 0, 0, pi], sign corrections [1, 1, -1, -1, -1, -1].
  // The j6 offset of pi only turns the end frame to ROS-Industrial's tool0; our flange frame F is parallel to R at
  // q = 0 (x along the flange normal), which R_EF absorbs. The wrist centre reaches a1 + c2 + hypot(a2, c3) =
  // 1420.5 mm from the j1 axis, matching the 1420 mm of the dissertation's Table 2.
  // Limits: J1 +-170 deg (340 deg data-sheet range); J2 -90..160, J3 -180..264, J4 +-190, J5 +-190, J6 +-360 deg
  // (the URDF's limits, serial j3 convention). Speeds 210, 190, 210, 400, 400, 600 deg/s (data sheet = URDF).
  OpwArm arm = FromParameters("FANUC ARC Mate 100iC/12", 150.0, -200.0, 0.0, 450.0, 600.0, 640.0, 100.0,
                              {0.0, 0.0, -kPi / 2, 0.0, 0.0, kPi}, {1, 1, -1, -1, -1, -1});
  arm.lower << Deg(-170), Deg(-90), Deg(-180), Deg(-190), Deg(-190), Deg(-360);
  arm.upper << Deg(170), Deg(160), Deg(264), Deg(190), Deg(190), Deg(360);
  arm.max_speed << Deg(210), Deg(190), Deg(210), Deg(400), Deg(400), Deg(600);
  arm.max_accel = arm.max_speed / kAxisRampTimeS;  // no data-sheet figure: the assumed ramp (opw_arm.h)
  return arm;
}

Eigen::Vector3d WristCentre(const OpwArm& arm, const Joints6& q) {
  // Forward position of the wrist centre C (Brandstoetter et al. 2014, eq. for c_x1, c_y1, c_z1 and c_0):
  // psi3 = atan2(a2, c3), k = hypot(a2, c3).
  const Joints6 t = ToOpw(arm, q);
  const double psi3 = std::atan2(arm.a2, arm.c3);
  const double k = std::hypot(arm.a2, arm.c3);
  const double cx1 = arm.c2 * std::sin(t[1]) + k * std::sin(t[1] + t[2] + psi3) + arm.a1;
  const double cz1 = arm.c2 * std::cos(t[1]) + k * std::cos(t[1] + t[2] + psi3);
  return Rz(t[0]) * Eigen::Vector3d(cx1, arm.b, cz1) + Eigen::Vector3d(0.0, 0.0, arm.c1);
}

Eigen::Isometry3d ForwardKinematics(const OpwArm& arm, const Joints6& q) {
  const Eigen::Matrix3d R_E = EndRotation(ToOpw(arm, q));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R_E * arm.R_EF;
  X.translation() = WristCentre(arm, q) + arm.c4 * R_E.col(2);
  return X;
}

namespace {

// What every branch of one flange pose shares: the end frame's orientation, the wrist centre and the seed.
struct IkPose {
  Eigen::Matrix3d R_E;
  Eigen::Vector3d w = Eigen::Vector3d::Zero();  // wrist centre in R, mm
  double rho2 = 0.0, h = 0.0, k = 0.0, psi3 = 0.0, planar = 0.0;
  Joints6 seed_t = Joints6::Zero();
  const Joints6* seed = nullptr;
};

// The pose's shared part; false when the wrist centre lies inside the cylinder of radius |b| about j1 that the arm
// plane cannot enter (`*excess` set).
bool PrepareIk(const OpwArm& arm, const Eigen::Isometry3d& X_RF, const Joints6* seed, IkPose* p, double* excess) {
  p->R_E = X_RF.linear() * arm.R_EF.transpose();
  // Wrist centre: back from the flange along the end frame's z by c4.
  p->w = X_RF.translation() - arm.c4 * p->R_E.col(2);
  p->rho2 = p->w.x() * p->w.x() + p->w.y() * p->w.y();
  p->h = p->w.z() - arm.c1;
  // Forearm as one rigid vector from j3 to the wrist centre: length k at angle psi3 from the forearm axis.
  p->k = std::hypot(arm.c3, arm.a2);
  p->psi3 = std::atan2(arm.a2, arm.c3);
  p->seed = seed;
  if (seed) p->seed_t = ToOpw(arm, *seed);
  if (p->rho2 < arm.b * arm.b - 1e-12) {
    *excess = std::max(1e-9, std::abs(arm.b) - std::sqrt(p->rho2));
    return false;
  }
  p->planar = std::sqrt(std::max(0.0, p->rho2 - arm.b * arm.b));  // |c_x1| in the arm plane
  return true;
}

// One shoulder's arm-plane solution: j1, the law-of-cosines term D and the direction gamma of the wrist centre.
struct ShoulderIk {
  double t1 = 0.0, D = 0.0, gamma = 0.0;
};

// Shoulder `shoulder` (0 front, 1 back); false when the wrist centre is out of its reach (`*excess` set, mm).
bool SolveShoulder(const OpwArm& arm, const IkPose& p, int shoulder, ShoulderIk* s, double* excess) {
  // Shoulder: the arm plane faces the wrist centre (front) or turns away from it (back, reaching over).
  const double cx1 = shoulder ? -p.planar : p.planar;
  if (p.rho2 < 1e-18) {
    s->t1 = p.seed_t[0] + (shoulder ? kPi : 0.0);  // shoulder singularity: j1 is free
  } else {
    s->t1 = std::atan2(p.w.y(), p.w.x()) - std::atan2(arm.b, cx1);  // paper: theta1 = atan2(c_y0, c_x0) - atan2(b, n_x1 + a1)
  }
  const double r = cx1 - arm.a1;  // horizontal distance j2 -> wrist centre in the arm plane
  const double s2 = r * r + p.h * p.h;
  // Law of cosines in the triangle j2 - j3 - wrist centre: the forearm vector turns by delta from the upper arm.
  s->D = (s2 - arm.c2 * arm.c2 - p.k * p.k) / (2.0 * arm.c2 * p.k);
  if (std::abs(s->D) > 1.0) {
    const double dist = std::sqrt(s2);
    const double over = s->D > 1.0 ? dist - (arm.c2 + p.k) : std::abs(arm.c2 - p.k) - dist;
    if (over > 1e-9) {
      *excess = over;
      return false;
    }
    s->D = std::clamp(s->D, -1.0, 1.0);
  }
  s->gamma = std::atan2(r, p.h);  // direction of the wrist centre from j2, from vertical towards +x
  return true;
}

// One elbow of a shoulder: j2, j3 and the wrist's matrix M = R_c^T R_E with its |sin j5|.
struct ElbowIk {
  double t2 = 0.0, t3 = 0.0, s5 = 0.0;
  Eigen::Matrix3d M;
};

ElbowIk SolveElbow(const OpwArm& arm, const IkPose& p, const ShoulderIk& sh, int elbow) {
  ElbowIk e;
  const double delta = (elbow ? -1.0 : 1.0) * std::acos(sh.D);
  e.t2 = sh.gamma - std::atan2(p.k * std::sin(delta), arm.c2 + p.k * std::cos(delta));
  e.t3 = delta - p.psi3;
  // Wrist: R_c^T R_E = Rz(t4) Ry(t5) Rz(t6), a Z-Y-Z Euler decomposition.
  e.M = (Rz(sh.t1) * Ry(e.t2 + e.t3)).transpose() * p.R_E;
  e.s5 = std::hypot(e.M(0, 2), e.M(1, 2));
  return e;
}

// One wrist branch (flip 0 or 1) of an elbow, in the arm's joints wrapped towards the seed; false for the second
// flip at the wrist singularity, where both coincide.
bool SolveWrist(const OpwArm& arm, const IkPose& p, const ShoulderIk& sh, const ElbowIk& e, int flip,
                IkSolution* sol) {
  double t4, t5, t6;
  const Eigen::Matrix3d& M = e.M;
  if (e.s5 < kWristSingularSin) {
    // t5 = 0 (or pi): only t4 + t6 (or t4 - t6) is defined; j4 keeps the seed.
    if (flip) return false;  // both wrist branches coincide
    t4 = p.seed_t[3];
    if (M(2, 2) > 0.0) {
      t5 = 0.0;
      t6 = std::atan2(M(1, 0), M(0, 0)) - t4;
    } else {
      t5 = kPi;
      t6 = t4 - std::atan2(-M(1, 0), M(1, 1));
    }
  } else {
    const double sg = flip ? -1.0 : 1.0;
    t5 = std::atan2(sg * e.s5, M(2, 2));
    t4 = std::atan2(sg * M(1, 2), sg * M(0, 2));
    t6 = std::atan2(sg * M(2, 1), -sg * M(2, 0));
  }
  Joints6 t;
  t << sh.t1, e.t2, e.t3, t4, t5, t6;
  for (int j = 0; j < 6; ++j) sol->q[j] = arm.sign_corrections[j] * (t[j] + arm.offsets[j]);
  const bool j5_positive = (std::abs(sol->q[4]) <= kPi ? sol->q[4] : std::remainder(sol->q[4], 2.0 * kPi)) > 0.0;
  sol->within_limits = true;
  for (int j = 0; j < 6; ++j) {
    const double target = p.seed ? (*p.seed)[j] : 0.0;
    sol->q[j] = NearestAngleCopy(sol->q[j], arm.lower[j], arm.upper[j], target);
    if (sol->q[j] < arm.lower[j] || sol->q[j] > arm.upper[j]) sol->within_limits = false;
  }
  sol->branch = (sol->opw_branch & 3) | (j5_positive ? 4 : 0);
  return true;
}

// Distance between two angles modulo 2 pi, in [0, pi], rad.
double AngleGap(double a) { return std::abs(std::abs(a) <= kPi ? a : std::remainder(a, 2.0 * kPi)); }

}  // namespace

IkSolutions SolveIk(const OpwArm& arm, const Eigen::Isometry3d& X_RF, const Joints6* seed) {
  IkSolutions out;
  IkPose p;
  if (!PrepareIk(arm, X_RF, seed, &p, &out.reach_excess_mm)) return out;
  double best_excess = std::numeric_limits<double>::infinity();
  for (int shoulder = 0; shoulder < 2; ++shoulder) {
    ShoulderIk sh;
    double excess = 0.0;
    if (!SolveShoulder(arm, p, shoulder, &sh, &excess)) {
      best_excess = std::min(best_excess, excess);
      continue;
    }
    for (int elbow = 0; elbow < 2; ++elbow) {
      const ElbowIk e = SolveElbow(arm, p, sh, elbow);
      for (int flip = 0; flip < 2; ++flip) {
        IkSolution& sol = out.solutions[out.count];
        sol.opw_branch = shoulder | (elbow << 1) | (flip << 2);
        if (SolveWrist(arm, p, sh, e, flip, &sol)) ++out.count;
      }
    }
  }
  if (out.count == 0) out.reach_excess_mm = best_excess;
  return out;
}

IkNearest SolveIkNearest(const OpwArm& arm, const Eigen::Isometry3d& X_RF, const Joints6& seed, int seed_branch) {
  IkNearest out;
  if (seed_branch >= 0 && seed_branch < 8) {
    IkPose p;
    ShoulderIk sh;
    double excess = 0.0;
    const int shoulder = seed_branch & 1, elbow = (seed_branch >> 1) & 1, flip = (seed_branch >> 2) & 1;
    if (PrepareIk(arm, X_RF, &seed, &p, &excess) && SolveShoulder(arm, p, shoulder, &sh, &excess)) {
      const ElbowIk e = SolveElbow(arm, p, sh, elbow);
      IkSolution sol;
      sol.opw_branch = seed_branch;
      if (e.s5 >= kWristSingularSin && SolveWrist(arm, p, sh, e, flip, &sol) && sol.within_limits) {
        // PickNearest's cost of this solution, and lower bounds on every other branch's: the wrist flip turns j4
        // and j6 by pi, the other elbow turns j3 by 2 acos(D), the other shoulder turns j1 by the difference of
        // the two atan2(b, +-c_x1); a branch that far from this one is at least (that gap - this one's step) from
        // the seed in that joint, whichever 2 pi copy the limits pick.
        Joints6 step = (sol.q - seed).cwiseAbs();
        double cost = 0.0;
        for (int j = 0; j < 6; ++j) cost += kWeight[j] * step[j] * step[j];
        const auto bound = [&](int j, double gap) {
          const double d = std::max(0.0, gap - step[j]);
          return kWeight[j] * d * d;
        };
        const double other_flip = bound(3, kPi) + bound(5, kPi);
        const double other_elbow = bound(2, AngleGap(2.0 * std::acos(sh.D)));
        const double other_shoulder =
            p.rho2 < 1e-18 ? bound(0, kPi) : bound(0, AngleGap(std::atan2(arm.b, p.planar) - std::atan2(arm.b, -p.planar)));
        // A margin against rounding in the two costs.
        if (cost < 0.5 * std::min({other_flip, other_elbow, other_shoulder})) {
          out.reachable = true;
          out.solution = sol;
          return out;
        }
      }
    }
  }
  const IkSolutions all = SolveIk(arm, X_RF, &seed);
  const int pick = PickNearest(arm, all, &seed);
  out.all_branches = true;
  if (pick < 0) {
    out.reach_excess_mm = all.reach_excess_mm;
    return out;
  }
  out.reachable = true;
  out.solution = all.solutions[pick];
  return out;
}

int PickNearest(const OpwArm& arm, const IkSolutions& solutions, const Joints6* seed) {
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
