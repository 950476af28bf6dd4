// Tests of the library of cells (cell.preset): every preset loads with the closed-form IK and its vendor name, its
// OPW parameters read off the joint axes are the published ones, IK then FK returns the pose on every branch, and
// the closed form agrees with MuJoCo's forward kinematics of the whole cell (flange and tool).
#include "twin/cell/cell_presets.h"

#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "analysis/cell_files.h"
#include "models/core/enum_names.h"
#include "models/core/numbers.h"
#include "planner/kinematics/opw_arm.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {
namespace {
using analysis::LoadCell;

double PoseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  // Position error in mm plus the rotation error expressed at 1000 mm lever arm.
  return (a.translation() - b.translation()).norm() + 1000.0 * (a.linear() - b.linear()).norm();
}

// The published OPW parameters (mm) of each preset's ROS-Industrial opw_parameters file, cited in the preset files.
struct Published {
  CellPreset preset;
  double a1, a2, b, c1, c2, c3, c4;
};
constexpr Published kPublished[] = {
    {CellPreset::kFanucArcMate100ic, 150, -200, 0, 450, 600, 640, 100},  // opw_parameters_m10ia.yaml (ARC Mate)
    {CellPreset::kAbbIrb1600, 150, 0, 0, 486.5, 700, 600, 65},         // opw_parameters_irb1600_8_145.yaml
    {CellPreset::kKukaKr16, 260, 35, 0, 675, 680, 670, 158},           // opw_parameters_kr16_2.yaml
    {CellPreset::kYaskawaMh12, 155, -200, 0, 450, 614, 640, 100},      // opw_parameters_mh12.yaml
};

CellModel LoadPreset(CellPreset preset) {
  CellSettings settings;
  ApplyPreset(preset, &settings);
  return LoadCell(settings);
}

class CellPresetTest : public ::testing::TestWithParam<Published> {};

TEST_P(CellPresetTest, LoadsWithTheClosedFormAndItsVendorName) {
  const Published& p = GetParam();
  const CellModel cell = LoadPreset(p.preset);
  EXPECT_TRUE(cell.closed_form()) << NameOf(p.preset) << ": " << cell.not_closed_form_reason();
  EXPECT_EQ(cell.robot().name, PresetInfo(p.preset).robot_name);
  EXPECT_EQ(cell.robot().source, NameOf(p.preset));
  EXPECT_FALSE(cell.kinematics().numeric_ik);
}

TEST_P(CellPresetTest, OpwParametersReadOffTheAxesAreThePublishedOnes) {
  const Published& p = GetParam();
  const planner::OpwArm arm = LoadPreset(p.preset).kinematics().arm;
  EXPECT_NEAR(arm.a1, p.a1, 1e-6) << NameOf(p.preset);
  EXPECT_NEAR(arm.a2, p.a2, 1e-6) << NameOf(p.preset);
  EXPECT_NEAR(arm.b, p.b, 1e-6) << NameOf(p.preset);
  EXPECT_NEAR(arm.c1, p.c1, 1e-6) << NameOf(p.preset);
  EXPECT_NEAR(arm.c2, p.c2, 1e-6) << NameOf(p.preset);
  EXPECT_NEAR(arm.c3, p.c3, 1e-6) << NameOf(p.preset);
  EXPECT_NEAR(arm.c4, p.c4, 1e-6) << NameOf(p.preset);
  // The published reach is the wrist centre of the stretched arm, a1 + c2 + hypot(a2, c3), within 5 %.
  const double stretched = p.a1 + std::hypot(p.c3, p.a2) + p.c2;
  EXPECT_NEAR(stretched, PresetInfo(p.preset).reach_mm, 0.05 * stretched) << NameOf(p.preset);
}

TEST_P(CellPresetTest, IkThenFkReturnsThePoseOnEveryBranch) {
  const Published& p = GetParam();
  const planner::OpwArm arm = LoadPreset(p.preset).kinematics().arm;
  std::mt19937_64 rng(4242 + static_cast<int>(p.preset));
  int branches_seen = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 2000; ++trial) {
    planner::Joints6 q;
    for (int j = 0; j < 6; ++j) q[j] = std::uniform_real_distribution<double>(arm.lower[j], arm.upper[j])(rng);
    const Eigen::Isometry3d X = planner::ForwardKinematics(arm, q);
    const planner::IkSolutions ik = planner::SolveIk(arm, X, nullptr);
    ASSERT_GT(ik.count, 0) << NameOf(p.preset) << ": a pose reached by FK must have an IK solution, trial " << trial;
    bool found_original = false;
    for (int i = 0; i < ik.count; ++i) {
      const double err = PoseError(planner::ForwardKinematics(arm, ik.solutions[i].q), X);
      worst = std::max(worst, err);
      ASSERT_LT(err, 1e-6) << NameOf(p.preset) << ": branch " << ik.solutions[i].branch << " of trial " << trial;
      Eigen::Matrix<double, 6, 1> d = ik.solutions[i].q - q;
      for (int j = 0; j < 6; ++j) d[j] = std::remainder(d[j], 2.0 * kPi);
      if (d.norm() < 1e-6) found_original = true;
      branches_seen |= 1 << ik.solutions[i].branch;
    }
    EXPECT_TRUE(found_original) << NameOf(p.preset) << ": the generating joints must be a branch, trial " << trial;
  }
  EXPECT_EQ(branches_seen, 0xFF) << NameOf(p.preset) << ": all 8 branches should occur";
  RecordProperty("worst_pose_error_mm", std::to_string(worst));
}

TEST_P(CellPresetTest, ClosedFormAgreesWithTheCellModelsTcp) {
  const Published& p = GetParam();
  const CellModel cell = LoadPreset(p.preset);
  const planner::CellKinematics kin = cell.kinematics();
  CellState state(cell);
  std::mt19937_64 rng(99 + static_cast<int>(p.preset));
  for (int trial = 0; trial < 200; ++trial) {
    planner::Joints8 q = planner::Joints8::Zero();
    for (int j = 0; j < 6; ++j) {
      q[j] = std::uniform_real_distribution<double>(kin.arm.lower[j], kin.arm.upper[j])(rng);
    }
    state.SetJoints(q);
    const Eigen::Isometry3d X_WT = kin.X_WR * planner::ForwardKinematics(kin.arm, q.head<6>()) * kin.X_FT;
    ASSERT_LT(PoseError(state.TcpPose(), X_WT), 1e-6) << NameOf(p.preset) << ", trial " << trial;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryPreset, CellPresetTest, ::testing::ValuesIn(kPublished),
                         [](const ::testing::TestParamInfo<Published>& info) {
                           return std::string(NameOf(info.param.preset));
                         });

TEST(CellPresets, EveryNameOfTheTableHasAnEntryAndAnInstalledModel) {
  for (const EnumName<CellPreset>& entry : EnumNames(CellPreset{})) {
    const CellPresetInfo& info = PresetInfo(entry.value);
    EXPECT_EQ(info.preset, entry.value);
    const std::filesystem::path urdf = PresetUrdf(entry.value);
    if (!info.urdf.empty()) {
      EXPECT_TRUE(std::filesystem::is_regular_file(urdf)) << urdf;
    }
  }
}

// Every preset has a program dialect for `waam export`, its vendor's: the names of both begin with the vendor.
TEST(CellPresets, EveryPresetExportsInItsVendorsDialect) {
  for (const EnumName<CellPreset>& entry : EnumNames(CellPreset{})) {
    const std::string preset(entry.name);
    const std::string dialect(NameOf(PresetDialect(entry.value)));
    EXPECT_EQ(preset.substr(0, preset.find('_')), dialect.substr(0, dialect.find('_'))) << preset << ": " << dialect;
  }
}

}  // namespace
}  // namespace waam::twin
