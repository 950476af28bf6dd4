// Tests of Dai et al.'s five-axis transform (sec. 3) against the positioner's closed form.
#include "models/core/numbers.h"
#include "planner/kinematics/five_axis.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "planner/kinematics/positioner.h"

namespace waam::planner {
namespace {

Eigen::Vector3d RandomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
}

TEST(FiveAxisTest, Solution2TurnsTheToolVectorToTheTarget) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d s = RandomUnit(rng), t = RandomUnit(rng);
    const Eigen::Matrix3d M = SolveDaiSolution2(s, t, nullptr);
    EXPECT_LT((M * s - t).norm(), 1e-9) << s.transpose() << " -> " << t.transpose();
    EXPECT_NEAR(M.determinant(), 1.0, 1e-12);
  }
}

TEST(FiveAxisTest, Solution1WhenRealTurnsTheToolVectorToTheTarget) {
  std::mt19937_64 rng(4);
  int real = 0;
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d s = RandomUnit(rng), t = RandomUnit(rng);
    for (bool branch : {true, false}) {
      const AxisAngles g = SolveDaiSolution1(s, t, branch);
      if (!g.real) {
        EXPECT_GT(t.x() * t.x() + s.z() * s.z(), 1.0 - 1e-9);
        continue;
      }
      ++real;
      const Eigen::Matrix4d M = DaiTransform(Eigen::Vector3d::Zero(), g);
      EXPECT_LT((M.topLeftCorner<3, 3>() * s - t).norm(), 1e-9);
    }
  }
  EXPECT_GT(real, 300);
}

TEST(FiveAxisTest, TransformKeepsTheCentreAndMatchesThePositionerAngles) {
  // The turntable: tilt about x, rotation about z (the chain of positioner.h with the part on the table axis).
  // Dai's solution 2 towards v_z gives the tilt a = acos(Z) and the turn c = pi/2 - atan2(Y, X): one of the two
  // closed-form solutions of SolvePositionerAngles; both put the tool vector along -gravity (torch along gravity).
  std::mt19937_64 rng(5);
  Positioner positioner;
  positioner.tilt_lower = -kPi;
  positioner.tilt_upper = kPi;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d n = RandomUnit(rng);
    AxisAngles g;
    const Eigen::Matrix3d M = SolveDaiSolution2(n, Eigen::Vector3d::UnitZ(), &g);
    const Eigen::Vector3d C(10, -20, 700);
    const Eigen::Matrix4d T = DaiTransform(C, g);
    EXPECT_LT((T.topLeftCorner<3, 3>() * C + T.topRightCorner<3, 1>() - C).norm(), 1e-9);
    EXPECT_LT((T.topLeftCorner<3, 3>() - M).norm(), 1e-12);
    const Eigen::Matrix3d R_table = PartPose(positioner, g.a, g.c).linear();
    EXPECT_LT((R_table * n - Eigen::Vector3d::UnitZ()).norm(), 1e-9);
    const PositionerAngles solved = SolvePositionerAngles(positioner, n, PositionerAngles{g.a, g.c});
    EXPECT_NEAR(solved.residual_rad, 0.0, 1e-6);
    EXPECT_NEAR(std::abs(solved.tilt), std::abs(g.a), 1e-9);
  }
}

}  // namespace
}  // namespace waam::planner
