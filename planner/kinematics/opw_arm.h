// Closed-form kinematics of six-axis arms with an ortho-parallel base and a spherical wrist (OPW family), in any
// vendor's joint zero and sign convention.
#pragma once

#include <array>
#include <optional>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "models/core/numbers.h"

namespace waam::planner {

using Joints6 = Eigen::Matrix<double, 6, 1>;  // arm joint angles j1..j6, rad

// The time an axis takes from rest to its rated speed when no acceleration is given, s. Data sheets (FANUC, ABB,
// KUKA, Yaskawa) list axis speeds only, and controllers keep their acceleration tables to themselves (KUKA's
// $ACC_MA, FANUC's acceleration time constants); 0.25 s is an assumed typical ramp of a 10-20 kg payload arm's
// servo axes (docs/TIMELINE.md), which `cell.axis_ramp_s` replaces with a measured one.
inline constexpr double kAxisRampTimeS = 0.25;

// Geometry, joint convention, limits and speeds of an OPW arm: the parameter set of Brandstoetter, Angerer and
// Hofbaur 2014 as the ROS-Industrial `opw_parameters_*.yaml` files give it (a1, a2, b, c1, c2, c3, c4, offsets,
// sign_corrections; lengths here in mm). The OPW model's own joints are q_opw[i] = sign_corrections[i] * q[i] -
// offsets[i]; at q_opw = 0 the arm stands straight up in the x-z plane of R, j1 turns about +z, j2 and j3 about +y,
// j4 about the forearm axis (+z of the wrist frame), j5 about its +y, j6 about the flange normal. The flange frame F
// that FK returns is the OPW end frame E (z along the flange normal) turned by R_EF, so F can be the vendor's
// (ROS-Industrial `tool0`) or ours (x along the flange normal). Frame R: on the j1 axis at the mounting surface.
struct OpwArm {
  std::string name;
  double a1 = 0.0;  // j2 axis offset from the j1 axis, mm
  double a2 = 0.0;  // forearm offset at j3 (negative: the forearm axis lies above j3 in the FANUC zero pose), mm
  double b = 0.0;   // lateral offset of the arm plane from the j1 axis, mm
  double c1 = 0.0;  // j2 axis height above the mounting surface, mm
  double c2 = 0.0;  // upper arm length j2 -> j3, mm
  double c3 = 0.0;  // forearm length j3 -> wrist centre, mm
  double c4 = 0.0;  // wrist centre -> flange, mm
  std::array<double, 6> offsets = {0, 0, 0, 0, 0, 0};           // rad
  std::array<int, 6> sign_corrections = {1, 1, 1, 1, 1, 1};     // +1 or -1
  Eigen::Matrix3d R_EF = Eigen::Matrix3d::Identity();            // flange frame F in the OPW end frame E
  Joints6 lower = Joints6::Constant(-kPi);      // joint limits, rad
  Joints6 upper = Joints6::Constant(kPi);       // rad
  Joints6 max_speed = Joints6::Constant(1.0);    // rad/s
  // rad/s^2: arm makers publish joint speeds but not accelerations; the default is each joint's speed reached in
  // kAxisRampTimeS (twin::CellSettings::axis_ramp_s sets it per cell).
  Joints6 max_accel = Joints6::Constant(1.0 / 0.25);

  // The FANUC ARC Mate 100iC/12 (= M-10iA arm) in FANUC's joint convention (serial j3), flange frame F with x
  // along the flange normal and F parallel to R at q = 0: reach 1420 mm, limits and speeds of its data sheet.
  static OpwArm ArcMate100iC12();
  // An arm from a ROS-Industrial OPW parameter set (lengths in mm, offsets in rad), flange frame = the OPW end frame
  // turned so that F has orientation R_RF0 in R at q = 0. Limits +-pi and speeds 1 rad/s until set.
  static OpwArm FromParameters(std::string name, double a1, double a2, double b, double c1, double c2, double c3,
                               double c4, const std::array<double, 6>& offsets,
                               const std::array<int, 6>& sign_corrections,
                               const Eigen::Matrix3d& R_RF0 = Eigen::Matrix3d::Identity());
};

// Flange pose X_RF (mm) for joint angles q (rad).
Eigen::Isometry3d ForwardKinematics(const OpwArm& arm, const Joints6& q);

// Wrist centre (intersection of j4, j5, j6) in R for joint angles q, mm.
Eigen::Vector3d WristCentre(const OpwArm& arm, const Joints6& q);

// One closed-form solution. `branch` bit 0: shoulder back (j1 turned away from the wrist centre), bit 1: elbow
// down, bit 2: wrist flipped (j5 > 0 in the arm's own convention). `within_limits` after wrapping every joint by
// 2 pi towards the seed.
struct IkSolution {
  Joints6 q = Joints6::Zero();
  int branch = 0;
  int opw_branch = 0;  // the OPW model's own branch: shoulder | elbow << 1 | flip << 2 (SolveIkNearest's key)
  bool within_limits = false;
};

// All closed-form solutions of the pose (at most 8).
struct IkSolutions {
  std::array<IkSolution, 8> solutions;
  int count = 0;
  // When count == 0: how far the wrist centre lies outside the reachable shell, mm (> 0).
  double reach_excess_mm = 0.0;
};

// Every inverse-kinematics branch of flange pose X_RF (mm). Joints are wrapped by multiples of 2 pi into their
// limits, as close as possible to `seed` (rad, may be null). At the wrist singularity (j5 = 0) j4 keeps the seed's
// value (0 without a seed) and j6 takes the rest; at the shoulder singularity j1 keeps the seed's value.
IkSolutions SolveIk(const OpwArm& arm, const Eigen::Isometry3d& X_RF, const Joints6* seed);

// The solution closest to `seed` (weighted joint distance, wrist joints count half) among those within limits;
// if none is within limits, the one that passes its limits least. Returns -1 when count == 0.
int PickNearest(const OpwArm& arm, const IkSolutions& solutions, const Joints6* seed);

// What SolveIkNearest found.
struct IkNearest {
  bool reachable = false;        // a solution exists
  IkSolution solution;           // the solution PickNearest would pick (when reachable)
  double reach_excess_mm = 0.0;  // when not reachable: as IkSolutions::reach_excess_mm, mm
  bool all_branches = false;     // every branch was solved (the seed's branch alone could not decide)
};

// The solution PickNearest(SolveIk(X_RF, &seed), &seed) picks, solving only the seed's branch `seed_branch`
// (IkSolution::opw_branch of the previous sample's solution; -1: unknown) when that decides it: the branch's
// solution within limits, away from the wrist singularity and closer to the seed, by a margin, than lower bounds on
// every other branch's distance (the wrist flip turns j4 and j6 by pi, the other elbow j3 by 2 acos D, the other
// shoulder j1 by the angle between the two arm planes). Otherwise every branch is solved. Same units as SolveIk.
IkNearest SolveIkNearest(const OpwArm& arm, const Eigen::Isometry3d& X_RF, const Joints6& seed, int seed_branch);

// Smallest distance of q to any joint limit, rad (negative when a joint is past its limit), and which joint.
double LimitMargin(const OpwArm& arm, const Joints6& q, int* joint);

// The six joint axes of an arm at q = 0 as a model draws them, in R: a point on each axis (mm) and its direction
// (unit; positive joint angles turn right-handed about it), and the flange pose.
struct ArmAxes {
  std::array<Eigen::Vector3d, 6> point_R;
  std::array<Eigen::Vector3d, 6> axis_R;
  Eigen::Isometry3d X_RF0 = Eigen::Isometry3d::Identity();
};

// The OPW parameters (with offsets, sign corrections and R_EF) of an arm drawn with the axes `axes`, whatever its
// joint zero and signs; nullopt with the reason in `why` (may be null) when the axes are not of the OPW kind (j1
// not along z of R through its origin, j2 and j3 not parallel and orthogonal to j1, j4-j6 not meeting in one point,
// the flange off the j6 axis). Limits and speeds are left at their defaults.
std::optional<OpwArm> OpwFromAxes(const ArmAxes& axes, std::string* why);

}  // namespace waam::planner
