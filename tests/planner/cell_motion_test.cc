// Tests of the coordinated motion: the TCP follows the path at the planned speed relative to the part, every
// sample's joints reproduce its torch pose, and the positioner reorients between layers during the travel move.
#include "planner/kinematics/cell_motion.h"

#include <cmath>

#include <gtest/gtest.h>

namespace waam::planner {
namespace {

CellKinematics DefaultCell() {
  CellKinematics cell;
  cell.arm = OpwArm::ArcMate100iC12();
  // Straight torch: TCP 400 mm along the flange normal, z_T = x_F, x_T = z_F (as in the built-in MJCF).
  cell.X_FT.translation() = Eigen::Vector3d(400.0, 0.0, 0.0);
  cell.X_FT.linear() << 0, 0, 1, 0, -1, 0, 1, 0, 0;
  cell.X_WB.translation() = Eigen::Vector3d(1050.0, 0.0, 0.0);
  cell.positioner.p_BA = Eigen::Vector3d(0.0, 0.0, 500.0);
  cell.positioner.p_AC = Eigen::Vector3d(0.0, 0.0, 80.0);
  cell.positioner.X_CP.translation() = Eigen::Vector3d(0.0, 0.0, 20.0);
  return cell;
}

Plan TwoLayers(const Eigen::Vector3d& second_build_dir) {
  Plan plan;
  for (int l = 0; l < 2; ++l) {
    LayerPath layer;
    layer.index = l;
    layer.build_dir_P = l == 0 ? Eigen::Vector3d::UnitZ() : second_build_dir.normalized();
    for (int i = 0; i < 4; ++i) {
      PathPoint p;
      p.p_P = Eigen::Vector3d(-30.0 + 20.0 * i, 10.0 * l, 2.0 * (l + 1));
      p.speed_mm_s = 7.5;
      p.weld = i > 0;
      p.tool_dir_P = layer.build_dir_P;
      layer.points.push_back(p);
    }
    plan.layers.push_back(layer);
  }
  return plan;
}

TEST(CellMotionTest, WeldMovesRunAtThePlannedSpeedRelativeToThePart) {
  const CellKinematics cell = DefaultCell();
  MotionOptions options;
  options.step_mm = 1.0;
  options.rapid_speed_mm_s = 100.0;
  const std::vector<CellSample> motion = PlanCellMotion(cell, TwoLayers(Eigen::Vector3d::UnitZ()), options, {});
  ASSERT_EQ(motion.size(), CountCellSamples(TwoLayers(Eigen::Vector3d::UnitZ()), 1.0));
  int weld_samples = 0;
  for (std::size_t i = 1; i < motion.size(); ++i) {
    if (!motion[i].weld) continue;
    const double v = (motion[i].p_P - motion[i - 1].p_P).norm() / motion[i].dt_s;
    EXPECT_NEAR(v, 7.5, 1e-9) << "sample " << i;
    EXPECT_LE((motion[i].p_P - motion[i - 1].p_P).norm(), 1.0 + 1e-9) << "samples at most step_mm apart";
    ++weld_samples;
  }
  EXPECT_EQ(weld_samples, 2 * 60);
}

TEST(CellMotionTest, JointsReproduceTheTorchPoseAndAreContinuous) {
  const CellKinematics cell = DefaultCell();
  const std::vector<CellSample> motion =
      PlanCellMotion(cell, TwoLayers(Eigen::Vector3d(1.0, 0.0, 1.0)), MotionOptions{}, {});
  for (std::size_t i = 0; i < motion.size(); ++i) {
    const CellSample& s = motion[i];
    ASSERT_TRUE(s.reachable) << "sample " << i;
    const Eigen::Isometry3d X_WT = cell.X_WR * ForwardKinematics(cell.arm, s.q.head<6>()) * cell.X_FT;
    EXPECT_LT((X_WT.translation() - s.X_WT.translation()).norm(), 1e-6) << "sample " << i;
    EXPECT_LT((X_WT.linear() - s.X_WT.linear()).norm(), 1e-9) << "sample " << i;
    // The TCP sits on the path point carried by the positioner.
    const Eigen::Vector3d p_W = cell.X_WB * PartPose(cell.positioner, s.q[6], s.q[7]) * s.p_P;
    EXPECT_LT((p_W - s.X_WT.translation()).norm(), 1e-9);
    if (i > 0) {
      EXPECT_LT((s.q - motion[i - 1].q).cwiseAbs().maxCoeff(), 0.2) << "no branch jump at sample " << i;
    }
  }
}

TEST(CellMotionTest, PositionerReorientsDuringTheTravelMoveIntoALayer) {
  const CellKinematics cell = DefaultCell();
  const std::vector<CellSample> motion =
      PlanCellMotion(cell, TwoLayers(Eigen::Vector3d(1.0, 0.0, 1.0)), MotionOptions{}, {});
  double first_layer_tilt = 0.0, second_layer_tilt = 0.0;
  for (const CellSample& s : motion) {
    if (s.layer == 0) first_layer_tilt = std::max(first_layer_tilt, std::abs(s.q[6]));
    if (s.layer == 1 && s.weld) second_layer_tilt = std::abs(s.q[6]);
    if (s.weld) {
      EXPECT_NEAR(s.torch_tilt_rad, 0.0, 1e-9) << "neutral position while welding";
    }
  }
  EXPECT_NEAR(first_layer_tilt, 0.0, 1e-12);
  EXPECT_NEAR(second_layer_tilt, M_PI / 4, 1e-9);
}

}  // namespace
}  // namespace waam::planner
