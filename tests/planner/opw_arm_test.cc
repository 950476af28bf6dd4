// Tests of the closed-form OPW kinematics: IK then FK returns the pose on every branch, unreachable poses say so.
#include "models/core/numbers.h"
#include "planner/kinematics/opw_arm.h"

#include <cmath>
#include <optional>
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

// Parameter sets as the ROS-Industrial support packages publish them (metres there, mm here), one per vendor
// convention, and one with a lateral offset b. Limits +-pi on j1-j5 and +-2 pi on j6 so every branch fits.
OpwArm Vendor(int which) {
  const double d90 = kPi / 2;
  OpwArm arm;
  switch (which) {
    case 0:  // fanuc_m10ia_support/config/opw_parameters_m10ia.yaml
      arm = OpwArm::FromParameters("FANUC M-10iA", 150, -200, 0, 450, 600, 640, 100, {0, 0, -d90, 0, 0, kPi},
                                   {1, 1, -1, -1, -1, -1});
      break;
    case 1:  // abb_irb1600_support/config/opw_parameters_irb1600_6_120.yaml
      arm = OpwArm::FromParameters("ABB IRB 1600-6/1.2", 150, 0, 0, 486.5, 475, 600, 65, {0, 0, -d90, 0, 0, 0},
                                   {1, 1, 1, 1, 1, 1});
      break;
    case 2:  // kuka_kr16_support/config/opw_parameters_kr16_2.yaml
      arm = OpwArm::FromParameters("KUKA KR 16-2", 260, 35, 0, 675, 680, 670, 158, {0, -d90, 0, 0, 0, 0},
                                   {-1, 1, 1, -1, 1, -1});
      break;
    case 3:  // motoman_mh12_support/config/opw_parameters_mh12.yaml
      arm = OpwArm::FromParameters("Yaskawa Motoman MH12", 155, -200, 0, 450, 614, 640, 100,
                                   {0, 0, -d90, 0, 0, kPi}, {1, 1, -1, -1, -1, -1});
      break;
    default:  // a lateral offset b (not in the four above), mixed signs and offsets
      arm = OpwArm::FromParameters("lateral offset", 100, -50, 80, 400, 500, 550, 90, {0.3, -0.2, 0.4, 0.1, -0.5, 1.0},
                                   {-1, 1, -1, 1, -1, 1});
      break;
  }
  arm.lower << -kPi, -kPi, -kPi, -kPi, -kPi, -2 * kPi;
  arm.upper << kPi, kPi, kPi, kPi, kPi, 2 * kPi;
  return arm;
}

class OpwVendorTest : public ::testing::TestWithParam<int> {};

TEST_P(OpwVendorTest, IkThenFkReturnsThePoseOnEveryBranch) {
  const OpwArm arm = Vendor(GetParam());
  std::mt19937_64 rng(777 + GetParam());
  int branches_seen = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Joints6 q = RandomJoints(arm, rng);
    const Eigen::Isometry3d X = ForwardKinematics(arm, q);
    const IkSolutions ik = SolveIk(arm, X, nullptr);
    ASSERT_GT(ik.count, 0) << arm.name << ": a pose reached by FK must have an IK solution, trial " << trial;
    bool found_original = false;
    for (int i = 0; i < ik.count; ++i) {
      const double err = PoseError(ForwardKinematics(arm, ik.solutions[i].q), X);
      worst = std::max(worst, err);
      ASSERT_LT(err, 1e-6) << arm.name << ": branch " << ik.solutions[i].branch << " of trial " << trial;
      Eigen::Matrix<double, 6, 1> d = ik.solutions[i].q - q;
      for (int j = 0; j < 6; ++j) d[j] = std::remainder(d[j], 2.0 * kPi);
      if (d.norm() < 1e-6) found_original = true;
      branches_seen |= 1 << ik.solutions[i].branch;
    }
    EXPECT_TRUE(found_original) << arm.name << ": the generating joints must be one of the branches, trial " << trial;
  }
  EXPECT_EQ(branches_seen, 0xFF) << arm.name << ": all 8 branches should occur";
  RecordProperty("worst_pose_error_mm", std::to_string(worst));
}

TEST_P(OpwVendorTest, ParametersAreReadBackFromTheJointAxes) {
  // Draw the arm's axes at q = 0 from its own FK (each joint's axis from the finite rotation it causes), then
  // OpwFromAxes must give an arm with the same FK everywhere (its offsets may differ by the j6 frame choice).
  const OpwArm arm = Vendor(GetParam());
  ArmAxes axes;
  const Eigen::Isometry3d X0 = ForwardKinematics(arm, Joints6::Zero());
  axes.X_RF0 = X0;
  for (int j = 0; j < 6; ++j) {
    Joints6 q = Joints6::Zero();
    q[j] = 0.5;
    // The flange moves by a rotation about joint j's axis: axis from the relative rotation, a point from the
    // fixed point of the motion (least squares of (I - R) p = t).
    const Eigen::Isometry3d X1 = ForwardKinematics(arm, q);
    const Eigen::Isometry3d M = X1 * X0.inverse();
    const Eigen::AngleAxisd aa(M.linear());
    axes.axis_R[j] = aa.axis() * (aa.angle() > 0 ? 1.0 : -1.0);
    const Eigen::Matrix3d I_R = Eigen::Matrix3d::Identity() - M.linear();
    axes.point_R[j] = I_R.completeOrthogonalDecomposition().solve(M.translation());
  }
  std::string why;
  const std::optional<OpwArm> read = OpwFromAxes(axes, &why);
  ASSERT_TRUE(read.has_value()) << arm.name << ": " << why;
  std::mt19937_64 rng(99);
  for (int trial = 0; trial < 500; ++trial) {
    const Joints6 q = RandomJoints(arm, rng);
    ASSERT_LT(PoseError(ForwardKinematics(*read, q), ForwardKinematics(arm, q)), 1e-6)
        << arm.name << ": the arm read from its axes must have the same FK, trial " << trial;
  }
}

INSTANTIATE_TEST_SUITE_P(Conventions, OpwVendorTest, ::testing::Values(0, 1, 2, 3, 4));

TEST(OpwArmTest, NonOpwAxesAreRefusedWithAReason) {
  ArmAxes axes;
  for (int j = 0; j < 6; ++j) {
    axes.point_R[j] = Eigen::Vector3d(0, 0, 100.0 * j);
    axes.axis_R[j] = Eigen::Vector3d::UnitY();
  }
  axes.axis_R[0] = Eigen::Vector3d::UnitX();
  std::string why;
  EXPECT_FALSE(OpwFromAxes(axes, &why).has_value());
  EXPECT_NE(why.find("j1"), std::string::npos) << why;
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

// The seed's branch alone answers as the full solve and PickNearest do, along random walks that pass near the
// singularities and the limits (steps up to 0.3 rad), and the walk does skip the full solve most of the time.
TEST(OpwArmTest, SeededBranchPicksWhatEveryBranchPicks) {
  const OpwArm arm = OpwArm::ArcMate100iC12();
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> step(-0.3, 0.3);
  int single = 0, poses = 0;
  for (int walk = 0; walk < 40; ++walk) {
    Joints6 q = RandomJoints(arm, rng);
    if (walk % 4 == 0) q[4] = 0.01 * step(rng);  // near the wrist singularity
    Joints6 seed = q;
    int branch = -1;
    for (int i = 0; i < 200; ++i, ++poses) {
      for (int j = 0; j < 6; ++j) q[j] = std::clamp(q[j] + step(rng) * (i % 10 == 0 ? 1.0 : 0.05), arm.lower[j], arm.upper[j]);
      const Eigen::Isometry3d X = ForwardKinematics(arm, q);
      const IkSolutions all = SolveIk(arm, X, &seed);
      const int pick = PickNearest(arm, all, &seed);
      const IkNearest one = SolveIkNearest(arm, X, seed, branch);
      ASSERT_EQ(one.reachable, pick >= 0) << "walk " << walk << " pose " << i;
      if (pick < 0) continue;
      EXPECT_EQ(one.solution.q, all.solutions[pick].q) << "walk " << walk << " pose " << i;
      EXPECT_EQ(one.solution.branch, all.solutions[pick].branch);
      EXPECT_EQ(one.solution.within_limits, all.solutions[pick].within_limits);
      if (!one.all_branches) ++single;
      seed = one.solution.q;
      branch = one.solution.opw_branch;
    }
  }
  EXPECT_GT(single, poses / 2) << "the seed's branch should decide most poses of a walk";
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
