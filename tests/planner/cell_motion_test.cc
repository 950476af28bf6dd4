// Tests of the coordinated motion: the TCP follows the path at the planned speed relative to the part, every
// sample's joints reproduce its torch pose, and the positioner reorients between layers during the travel move.
#include "models/core/numbers.h"
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
  EXPECT_NEAR(second_layer_tilt, kPi / 4, 1e-9);
}

TEST(CellMotionTest, PositionerTurnsAlongTheWholeLayerWhenTheLayerIsEnteredWelding) {
  // A spiral: the second layer is entered by a weld move (61 mm), with no arc-off move to turn the positioner in.
  // The turn is spread over the entry move and the layer (61 + 60 mm), not done within the entry move.
  Plan plan = TwoLayers(Eigen::Vector3d(1.0, 0.0, 1.0));
  plan.layers[1].points.front().weld = true;
  const std::vector<CellSample> motion = PlanCellMotion(DefaultCell(), plan, MotionOptions{}, {});
  const int entry_point = static_cast<int>(plan.layers[0].points.size());  // global index of layer 1's point 0
  double at_entry_end = -1.0, last = 0.0, previous = 0.0;
  for (const CellSample& s : motion) {
    if (s.layer != 1) continue;
    EXPECT_GE(std::abs(s.q[6]), previous - 1e-12) << "the tilt rises steadily, sample at point " << s.point;
    previous = std::abs(s.q[6]);
    if (s.point == entry_point) at_entry_end = std::abs(s.q[6]);
    last = std::abs(s.q[6]);
  }
  const double entry = (plan.layers[1].points.front().p_P - plan.layers[0].points.back().p_P).norm();
  EXPECT_NEAR(at_entry_end, kPi / 4 * entry / (entry + 60.0), 1e-9) << "about half way along the turning path";
  EXPECT_NEAR(last, kPi / 4, 1e-9);
}

TEST(CellMotionTest, PerPointPositionerKeepsTheTorchVerticalOnACurvedLayer) {
  // One ring whose local normals lean 25 deg outwards (a conical layer): the positioner follows every point.
  const CellKinematics cell = DefaultCell();
  Plan plan;
  LayerPath layer;
  const double lean = 25.0 * kPi / 180.0;
  for (int i = 0; i <= 72; ++i) {
    const double a = 2.0 * kPi * i / 72;
    PathPoint p;
    p.p_P = Eigen::Vector3d(40.0 * std::cos(a), 40.0 * std::sin(a), 10.0);
    p.tool_dir_P = Eigen::Vector3d(std::sin(lean) * std::cos(a), std::sin(lean) * std::sin(a), std::cos(lean));
    p.speed_mm_s = 7.5;
    p.weld = i > 0;
    layer.points.push_back(p);
  }
  plan.layers.push_back(layer);
  MotionOptions options;
  options.positioner_per_point = true;
  const std::vector<CellSample> motion = PlanCellMotion(cell, plan, options, {});
  double rotation_min = 1e9, rotation_max = -1e9;
  for (const CellSample& s : motion) {
    EXPECT_NEAR(s.torch_tilt_rad, 0.0, 1e-7) << "the positioner turns every local normal up";
    // Between path points the interpolated normal leans a little less than at them.
    EXPECT_LE(std::abs(s.q[6]), lean + 1e-9);
    EXPECT_GE(std::abs(s.q[6]), lean - 1e-3);
    rotation_min = std::min(rotation_min, s.q[7]);
    rotation_max = std::max(rotation_max, s.q[7]);
  }
  // A full turn of the normal needs 360 deg of table rotation; starting at +-90 deg, the +-240 deg range forces one
  // switch to the other solution (tilt sign flipped, rotation shifted by 180 deg) but never leaves the range.
  EXPECT_GE(rotation_min, cell.positioner.rotation_lower);
  EXPECT_LE(rotation_max, cell.positioner.rotation_upper);
  EXPECT_GT(rotation_max - rotation_min, kPi) << "the table follows the normal around";
  options.positioner_per_point = false;
  const std::vector<CellSample> per_layer = PlanCellMotion(cell, plan, options, {});
  EXPECT_NEAR(per_layer.back().torch_tilt_rad, lean, 1e-9) << "per layer, the torch follows the leaning normal";
}

}  // namespace
}  // namespace waam::planner
