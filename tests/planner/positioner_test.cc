// Tests of the positioner angles: known build directions are turned to vertical, or held at the tilt limit.
#include "models/core/numbers.h"
#include "planner/kinematics/positioner.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace waam::planner {
namespace {

Eigen::Vector3d Turned(const Positioner& pos, const PositionerAngles& a, const Eigen::Vector3d& n_P) {
  return PartPose(pos, a.tilt, a.rotation).linear() * n_P.normalized();
}

TEST(PositionerTest, KnownNormalsTurnToVertical) {
  const Positioner pos;
  const Eigen::Vector3d normals[] = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {-1, 0.5, 2}, {0.3, -0.8, 0.6}, {1, 1, 0.8}};
  for (const Eigen::Vector3d& n : normals) {
    const PositionerAngles a = SolvePositionerAngles(pos, n, PositionerAngles{});
    EXPECT_FALSE(a.at_limit) << "normal " << n.transpose() << " is within 70 deg of vertical";
    EXPECT_NEAR(Turned(pos, a, n).z(), 1.0, 1e-12) << "normal " << n.transpose() << " must point up";
    EXPECT_NEAR(a.residual_rad, 0.0, 1e-6);
    // The tilt equals the angle of the normal from the table axis (eq. 5.13, third line).
    EXPECT_NEAR(std::abs(a.tilt), std::acos(n.normalized().z()), 1e-12);
  }
}

TEST(PositionerTest, RandomNormalsWithPartTurnedOnThePlate) {
  Positioner pos;
  pos.X_CP = Eigen::Translation3d(30.0, -20.0, 25.0) * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ());
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  PositionerAngles previous;
  for (int i = 0; i < 500; ++i) {
    Eigen::Vector3d n(g(rng), g(rng), std::abs(g(rng)) + 0.4);  // within the tilt range
    n.normalize();
    if (std::acos(n.z()) > pos.tilt_upper) continue;
    const PositionerAngles a = SolvePositionerAngles(pos, n, previous);
    EXPECT_NEAR(Turned(pos, a, n).z(), 1.0, 1e-9) << "normal " << n.transpose();
    EXPECT_GE(a.rotation, pos.rotation_lower);
    EXPECT_LE(a.rotation, pos.rotation_upper);
    previous = a;
  }
}

TEST(PositionerTest, NearestSolutionFollowsThePreviousAngles) {
  const Positioner pos;
  const Eigen::Vector3d n(1.0, 0.0, 1.0);
  PositionerAngles prev;
  prev.tilt = -0.7;
  prev.rotation = -1.5;
  const PositionerAngles a = SolvePositionerAngles(pos, n, prev);
  EXPECT_LT(a.tilt, 0.0) << "the negative-tilt solution is nearer the previous angles";
  prev.tilt = 0.7;
  prev.rotation = 1.5;
  const PositionerAngles b = SolvePositionerAngles(pos, n, prev);
  EXPECT_GT(b.tilt, 0.0);
  EXPECT_NEAR(Turned(pos, a, n).z(), 1.0, 1e-12);
  EXPECT_NEAR(Turned(pos, b, n).z(), 1.0, 1e-12);
}

TEST(PositionerTest, VerticalNormalKeepsTheRotation) {
  const Positioner pos;
  PositionerAngles prev;
  prev.rotation = 1.2;
  const PositionerAngles a = SolvePositionerAngles(pos, Eigen::Vector3d::UnitZ(), prev);
  EXPECT_DOUBLE_EQ(a.tilt, 0.0);
  EXPECT_DOUBLE_EQ(a.rotation, 1.2);
}

TEST(PositionerTest, PastTheTiltRangeHoldsTheLimitAndReportsTheTorchTilt) {
  const Positioner pos;  // +-70 deg
  const double angle = 85.0 * kPi / 180.0;
  const Eigen::Vector3d n(std::sin(angle), 0.0, std::cos(angle));
  const PositionerAngles a = SolvePositionerAngles(pos, n, PositionerAngles{});
  EXPECT_TRUE(a.at_limit);
  EXPECT_NEAR(std::abs(a.tilt), 70.0 * kPi / 180.0, 1e-12) << "the tilt stays at its limit";
  EXPECT_NEAR(a.residual_rad, 15.0 * kPi / 180.0, 1e-9) << "the torch makes up the remaining 15 deg";
  EXPECT_NEAR(Turned(pos, a, n).z(), std::cos(a.residual_rad), 1e-12);
}

TEST(PositionerTest, TurntableOnlyTurnsAndLeavesTheAngleToVertical) {
  // A turntable cannot tilt: the tilt stays 0, the rotation keeps the previous one, and what is left for the torch
  // is the build direction's whole angle to vertical.
  Positioner pos;
  pos.type = PositionerType::kTurntable;
  pos.X_CP = Eigen::Translation3d(30.0, -20.0, 25.0) * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ());
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g(0.0, 1.0);
  PositionerAngles previous;
  previous.rotation = 1.25;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d n = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    const PositionerAngles a = SolvePositionerAngles(pos, n, previous);
    EXPECT_EQ(a.tilt, 0.0);
    EXPECT_EQ(a.rotation, previous.rotation);
    EXPECT_NEAR(a.residual_rad, std::acos(n.z()), 1e-9) << "the plate stays level: the angle is the part frame's";
    EXPECT_NEAR(std::cos(a.residual_rad), Turned(pos, a, n).z(), 1e-12);
    EXPECT_EQ(a.at_limit, a.residual_rad > 1e-6);
  }
  EXPECT_FALSE(SolvePositionerAngles(pos, Eigen::Vector3d::UnitZ(), previous).at_limit);
}

TEST(PositionerTest, NoPositionerTurnsNothing) {
  Positioner pos;
  pos.type = PositionerType::kNone;
  PositionerAngles previous;
  previous.tilt = 0.4;
  previous.rotation = 1.25;
  const Eigen::Vector3d n = Eigen::Vector3d(1.0, 0.0, 1.0).normalized();
  const PositionerAngles a = SolvePositionerAngles(pos, n, previous);
  EXPECT_EQ(a.tilt, 0.0);
  EXPECT_EQ(a.rotation, 0.0);
  EXPECT_NEAR(a.residual_rad, kPi / 4, 1e-12);
  EXPECT_TRUE(a.at_limit);
  EXPECT_TRUE(HasAxis(PositionerType::kTiltRotate, 6));
  EXPECT_FALSE(HasAxis(PositionerType::kTurntable, 6));
  EXPECT_TRUE(HasAxis(PositionerType::kTurntable, 7));
  EXPECT_FALSE(HasAxis(PositionerType::kNone, 7));
  EXPECT_TRUE(HasAxis(PositionerType::kNone, 5));
}

}  // namespace
}  // namespace waam::planner
