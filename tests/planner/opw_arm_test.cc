// Tests of the closed-form OPW kinematics: IK then FK returns the pose on every branch, unreachable poses say so.
#include "models/core/numbers.h"
#include "planner/kinematics/opw_arm.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace waam::planner {
namespace {

Joints6 RandomJoints(const OpwArm& arm, std::mt19937_64& rng) {
  Joints6 q;
  for (int j = 0; j < 6; ++j) {
    std::uniform_real_distribution<double> u(arm.lower[j], arm.upper[j]);
    q[j] = u(rng);
  }
  return q;
}

double PoseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  // Position error in mm plus the rotation error expressed at 1000 mm lever arm.
  return (a.translation() - b.translation()).norm() + 1000.0 * (a.linear() - b.linear()).norm();
}

TEST(OpwArmTest, ZeroPoseMatchesPublishedGeometry) {
  const OpwArm arm = OpwArm::ArcMate100iC12();
  const Eigen::Isometry3d X = ForwardKinematics(arm, Joints6::Zero());
  // Flange at a1 + c3 + c4 forward and c1 + c2 - a2 up, axes parallel to the base.
  EXPECT_NEAR(X.translation().x(), 150.0 + 640.0 + 100.0, 1e-9);
  EXPECT_NEAR(X.translation().y(), 0.0, 1e-9);
  EXPECT_NEAR(X.translation().z(), 450.0 + 600.0 + 200.0, 1e-9);
  EXPECT_TRUE(X.linear().isIdentity(1e-12));
  // Reach of the wrist centre from the j1 axis, stretched forward: 1420 mm class (Table 2).
  const double reach = arm.a1 + arm.c2 + std::hypot(arm.a2, arm.c3);
  EXPECT_NEAR(reach, 1420.0, 1.0);
}

TEST(OpwArmTest, IkThenFkReturnsThePoseOnEveryBranch) {
  const OpwArm arm = OpwArm::ArcMate100iC12();
  std::mt19937_64 rng(12345);
  int checked = 0;
  int branches_seen = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Joints6 q = RandomJoints(arm, rng);
    const Eigen::Isometry3d X = ForwardKinematics(arm, q);
    const IkSolutions ik = SolveIk(arm, X, nullptr);
    ASSERT_GT(ik.count, 0) << "a pose reached by FK must have an IK solution, trial " << trial;
    bool found_original = false;
    for (int i = 0; i < ik.count; ++i) {
      const double err = PoseError(ForwardKinematics(arm, ik.solutions[i].q), X);
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-6) << "branch " << ik.solutions[i].branch << " of trial " << trial << " misses the pose";
      Eigen::Matrix<double, 6, 1> d = ik.solutions[i].q - q;
      for (int j = 0; j < 6; ++j) d[j] = std::remainder(d[j], 2.0 * kPi);
      if (d.norm() < 1e-6) found_original = true;
      branches_seen |= 1 << ik.solutions[i].branch;
      ++checked;
    }
    EXPECT_TRUE(found_original) << "the generating joints must be one of the branches, trial " << trial;
  }
  EXPECT_EQ(branches_seen, 0xFF) << "all 8 branches should occur";
  EXPECT_GT(checked, 4000 * 4);
  RecordProperty("worst_pose_error_mm", std::to_string(worst));
}

TEST(OpwArmTest, SeedKeepsTheBranchAndWrapsJ6) {
  const OpwArm arm = OpwArm::ArcMate100iC12();
  Joints6 q;
  q << 0.3, 0.2, -0.1, 0.4, -1.0, 5.0;  // j6 beyond +pi: the IK must return the wrapped copy near the seed
  const IkSolutions ik = SolveIk(arm, ForwardKinematics(arm, q), &q);
  const int pick = PickNearest(arm, ik, &q);
  ASSERT_GE(pick, 0);
  EXPECT_LT((ik.solutions[pick].q - q).norm(), 1e-9) << "the nearest branch to its own joints is itself";
}

TEST(OpwArmTest, WristSingularityKeepsJ4) {
  const OpwArm arm = OpwArm::ArcMate100iC12();
  Joints6 q;
  q << 0.1, 0.3, 0.2, 0.7, 0.0, -0.2;
  const IkSolutions ik = SolveIk(arm, ForwardKinematics(arm, q), &q);
  const int pick = PickNearest(arm, ik, &q);
  ASSERT_GE(pick, 0);
  EXPECT_NEAR(ik.solutions[pick].q[3], 0.7, 1e-9) << "j4 keeps the seed at j5 = 0";
  EXPECT_LT(PoseError(ForwardKinematics(arm, ik.solutions[pick].q), ForwardKinematics(arm, q)), 1e-6);
}

TEST(OpwArmTest, UnreachablePoseIsReportedWithItsDistance) {
  const OpwArm arm = OpwArm::ArcMate100iC12();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(2000.0, 0.0, 450.0);  // wrist centre 1900 mm out, 1850 from j2
  const IkSolutions ik = SolveIk(arm, X, nullptr);
  EXPECT_EQ(ik.count, 0);
  const double k = std::hypot(arm.c3, arm.a2);
  EXPECT_NEAR(ik.reach_excess_mm, (1900.0 - arm.a1) - (arm.c2 + k), 1e-6);
  EXPECT_EQ(PickNearest(arm, ik, nullptr), -1);
}

TEST(OpwArmTest, LimitMarginNamesTheJoint) {
  const OpwArm arm = OpwArm::ArcMate100iC12();
  Joints6 q = Joints6::Zero();
  q[0] = arm.upper[0] + 0.1;
  int joint = -1;
  EXPECT_NEAR(LimitMargin(arm, q, &joint), -0.1, 1e-12);
  EXPECT_EQ(joint, 0);
}

}  // namespace
}  // namespace waam::planner
