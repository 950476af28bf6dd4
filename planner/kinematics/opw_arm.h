// Closed-form kinematics of six-axis arms with an ortho-parallel base and a spherical wrist (OPW family).
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "models/core/numbers.h"

namespace waam::planner {

using Joints6 = Eigen::Matrix<double, 6, 1>;  // arm joint angles j1..j6, rad

// Geometry, limits and speeds of an OPW arm (Brandstoetter, Angerer, Hofbaur 2014 parameters, lateral offset b = 0).
// Joint convention (the FANUC serial one of the ROS-Industrial models): at q = 0 the upper arm is vertical, the
// forearm horizontal along +x of the base frame R, and the flange normal is +x of the flange frame F, whose axes are
// then parallel to R. j1 turns about +z of R, j2 about +y (positive leans the upper arm forward), j3 about -y
// (positive raises the forearm), j4 about -x, j5 about -y, j6 about -x of the frames before them.
// Frame R: on the j1 axis at the mounting surface. All lengths in mm.
struct OpwArm {
  std::string name;
  double a1 = 0.0;  // j2 axis offset from the j1 axis, mm
  double a2 = 0.0;  // forearm offset at j3 (negative: the forearm axis lies above j3 in the zero pose), mm
  double c1 = 0.0;  // j2 axis height above the mounting surface, mm
  double c2 = 0.0;  // upper arm length j2 -> j3, mm
  double c3 = 0.0;  // forearm length j3 -> wrist centre, mm
  double c4 = 0.0;  // wrist centre -> flange, mm
  Joints6 lower = Joints6::Constant(-kPi);      // joint limits, rad
  Joints6 upper = Joints6::Constant(kPi);       // rad
  Joints6 max_speed = Joints6::Constant(1.0);    // rad/s

  // The FANUC ARC Mate 100iC/12 (= M-10iA arm): reach 1420 mm, limits and speeds of its data sheet.
  static OpwArm ArcMate100iC12();
};

// Flange pose X_RF (mm) for joint angles q (rad).
Eigen::Isometry3d ForwardKinematics(const OpwArm& arm, const Joints6& q);

// Wrist centre (intersection of j4, j5, j6) in R for joint angles q, mm.
Eigen::Vector3d WristCentre(const OpwArm& arm, const Joints6& q);

// One closed-form solution. `branch` bit 0: shoulder back (j1 turned away from the wrist centre), bit 1: elbow
// down, bit 2: wrist flipped (j5 > 0). `within_limits` after wrapping every joint by 2 pi towards the seed.
struct IkSolution {
  Joints6 q = Joints6::Zero();
  int branch = 0;
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

// Smallest distance of q to any joint limit, rad (negative when a joint is past its limit), and which joint.
double LimitMargin(const OpwArm& arm, const Joints6& q, int* joint);

}  // namespace waam::planner
