// Tests of cell.positioner.type: the MuJoCo model of a turntable or no-positioner cell really lacks the missing axes
// and its part pose agrees with planner::PartPose; a wall checks end to end on each; a tilted wall on a cell that
// cannot turn it up is welded with the torch tilted; the presets with each type; bad input.
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <string>

#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "analysis/cell_files.h"
#include "models/core/numbers.h"
#include "models/core/yaml_map.h"
#include "tests/twin/test_plans.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/cell_compose.h"
#include "twin/cell/cell_presets.h"
#include "twin/cell/cell_section.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {
using analysis::LoadCell;
// Named, not anonymous: the tests compile as unity batches, where anonymous namespaces of several files merge.
namespace positioner_types_test {
namespace fs = std::filesystem;
using planner::PositionerType;
using ::testing::HasSubstr;

std::string Describe(const CheckReport& r) {
  std::string text;
  for (const CheckViolation& v : r.violations) {
    text += std::string(NameOf(v.kind)) + " " + v.joint + v.body1 + "/" + v.body2 + " at point " + std::to_string(v.point) + " value " +
            std::to_string(v.value) + " " + v.unit + "\n";
  }
  return text;
}

CellSettings PresetSettings(CellPreset preset) {
  CellSettings settings;
  ApplyPreset(preset, &settings);
  return settings;
}

// The body of `model` named `name`, or null.
const CellBody* FindBody(const std::vector<CellBody>& bodies, const std::string& name) {
  for (const CellBody& b : bodies) {
    if (b.name == name) return &b;
  }
  return nullptr;
}

// The cells of each type: the two presets built for them, and the built-in FANUC arm with its positioner replaced.
struct TypedCell {
  const char* name;
  CellSettings settings;
  PositionerType type;
};

std::vector<TypedCell> TypedCells() {
  CellSettings fanuc_turntable, fanuc_none;
  fanuc_turntable.positioner_type = PositionerType::kTurntable;
  fanuc_none.positioner_type = PositionerType::kNone;
  return {{"kuka_kr16_turntable", PresetSettings(CellPreset::kKukaKr16Turntable), PositionerType::kTurntable},
          {"abb_irb1600_table", PresetSettings(CellPreset::kAbbIrb1600Table), PositionerType::kNone},
          {"builtin_turntable", fanuc_turntable, PositionerType::kTurntable},
          {"builtin_none", fanuc_none, PositionerType::kNone}};
}

TEST(PositionerTypes, TheModelHasExactlyTheAxesOfItsType) {
  for (const TypedCell& c : TypedCells()) {
    const CellModel model = LoadCell(c.settings);
    EXPECT_EQ(model.kinematics().positioner.type, c.type) << c.name;
    std::set<std::string> joints;
    for (const CellBody& b : model.Bodies()) {
      if (!b.joint.empty()) joints.insert(b.joint);
    }
    EXPECT_EQ(joints.count("pos_tilt"), 0u) << c.name;
    EXPECT_EQ(joints.count("pos_rot"), c.type == PositionerType::kTurntable ? 1u : 0u) << c.name;
    EXPECT_EQ(FindBody(model.Bodies(), "tilt"), nullptr) << c.name;
    EXPECT_NE(FindBody(model.Bodies(), "substrate"), nullptr) << c.name;
  }
}

TEST(PositionerTypes, PartPoseAgreesWithTheModelAndMissingAxesMoveNothing) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  for (const TypedCell& c : TypedCells()) {
    const CellModel model = LoadCell(c.settings);
    const planner::CellKinematics kin = model.kinematics();
    const std::vector<CellBody> bodies = model.Bodies();
    std::size_t substrate = 0;
    while (bodies[substrate].name != "substrate") ++substrate;
    CellState state(model);
    for (int trial = 0; trial < 50; ++trial) {
      planner::Joints8 q = planner::Joints8::Zero();
      for (int j = 0; j < 8; ++j) q[j] = angle(rng);
      state.SetJoints(q);
      // The plate top (part_origin, 20 mm above the substrate body's origin) where the planner puts the part
      // frame at zero offset: the tilt never counts, the rotation only on a turntable.
      Eigen::Isometry3d X_WO = state.BodyPoses()[substrate];
      X_WO.translate(Eigen::Vector3d(0.0, 0.0, 20.0));
      const double rotation = c.type == PositionerType::kTurntable ? q[7] : 0.0;
      const Eigen::Isometry3d X_WP = kin.X_WB * planner::PartPose(kin.positioner, 0.0, rotation);
      ASSERT_LT((X_WO.translation() - X_WP.translation()).norm(), 1e-6) << c.name << ", trial " << trial;
      ASSERT_LT((X_WO.linear() - X_WP.linear()).norm(), 1e-9) << c.name << ", trial " << trial;
    }
  }
}

TEST(PositionerTypes, PlanarWallPassesOnEveryType) {
  for (const TypedCell& c : TypedCells()) {
    CellSettings settings = c.settings;
    settings.positioner_rotation_deg = 30.0;
    const CheckReport r =
        CheckPlan(LoadCell(settings), testing::RectangleWall(6, 100.0, 60.0, 1.5, 400.0 / 60.0), settings, 100.0,
                  nullptr);
    EXPECT_TRUE(r.ok) << c.name << ":\n" << Describe(r);
    EXPECT_EQ(r.positioner_type, c.type) << c.name;
    EXPECT_EQ(r.positioner_limit_layers, 0) << c.name;
    EXPECT_LT(r.max_torch_tilt_deg, 1e-6) << c.name << ": a planar wall is welded with a vertical torch";
    EXPECT_NE(r.min_margin_joint, "pos_tilt") << c.name;
    EXPECT_NE(r.min_margin_joint, "pos_rot") << c.name;
    const double rotation = c.type == PositionerType::kTurntable ? 30.0 * kPi / 180.0 : 0.0;
    for (const planner::CellSample& s : r.motion) {
      ASSERT_EQ(s.q[6], 0.0) << c.name << ": the cell has no tilt axis";
      ASSERT_NEAR(s.q[7], rotation, 1e-12) << c.name;
    }
  }
}

// A wall whose layers grow 30 deg off the plate normal (as the tilt_rotate cell's TiltedBuildDirection test).
planner::Plan TiltedWall(double tilt_deg) {
  planner::Plan plan = testing::RectangleWall(5, 60.0, 40.0, 1.5, 400.0 / 60.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(tilt_deg * kPi / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (planner::LayerPath& layer : plan.layers) {
    layer.build_dir_P = R * Eigen::Vector3d::UnitZ();
    for (planner::PathPoint& p : layer.points) {
      p.p_P = R * p.p_P + Eigen::Vector3d(0.0, 0.0, 20.0);
      p.tool_dir_P = layer.build_dir_P;
    }
  }
  return plan;
}

TEST(PositionerTypes, TiltedLayersAreWeldedWithTheTorchTiltedWhereNothingTurnsThemUp) {
  for (const TypedCell& c : TypedCells()) {
    const CheckReport r = CheckPlan(LoadCell(c.settings), TiltedWall(30.0), c.settings, 100.0, nullptr);
    // Nothing tilts the part: the torch follows the tool direction, 30 deg from vertical, and every layer is
    // counted as needing more tilt than the positioner has.
    EXPECT_NEAR(r.max_torch_tilt_deg, 30.0, 1e-6) << c.name;
    EXPECT_EQ(r.positioner_limit_layers, 5) << c.name;
    for (const planner::CellSample& s : r.motion) {
      if (s.weld) {
        ASSERT_NEAR(s.torch_tilt_rad * 180.0 / kPi, 30.0, 1e-6) << c.name;
      }
    }
    // The arm keeps that torch angle: every sample reachable, within its limits.
    EXPECT_TRUE(r.ok) << c.name << ":\n" << Describe(r);
  }
}

TEST(PositionerTypes, WhereTheArmCannotKeepTheTorchAngleTheCheckSaysWhere) {
  // Layers growing 100 deg off the plate normal (past horizontal) on a fixed table: the torch would have to point up
  // from below the work. The check fails and says where: the wrist at its limit (j5) and the torch in the table.
  const TypedCell c = TypedCells()[1];
  const CheckReport r = CheckPlan(LoadCell(c.settings), TiltedWall(100.0), c.settings, 100.0, nullptr);
  EXPECT_FALSE(r.ok);
  bool wrist = false, table = false;
  for (const CheckViolation& v : r.violations) {
    wrist |= v.kind == ViolationKind::kJointLimit && v.joint == "j5";
    table |= v.kind == ViolationKind::kCollision && v.body1 == "positioner_base" && v.body2 == "torch";
    EXPECT_NE(v.joint, "pos_tilt");
    EXPECT_NE(v.joint, "pos_rot");
  }
  EXPECT_TRUE(wrist) << Describe(r);
  EXPECT_TRUE(table) << Describe(r);
}

TEST(PositionerTypes, ComposedBuiltinCellKeepsTheArmOfTheFile) {
  // The built-in FANUC arm is the file's whatever the positioner: same closed form, same tool.
  const CellModel file = LoadCell(CellSettings{});
  for (const TypedCell& c : TypedCells()) {
    if (c.settings.preset) continue;
    const CellModel composed = LoadCell(c.settings);
    EXPECT_TRUE(composed.closed_form()) << c.name;
    EXPECT_EQ(composed.robot().name, file.robot().name);
    EXPECT_LT((composed.kinematics().X_FT.matrix() - file.kinematics().X_FT.matrix()).norm(), 1e-12) << c.name;
    planner::Joints6 q;
    q << 0.3, 0.2, -0.1, 0.5, -1.0, 0.7;
    const Eigen::Isometry3d a = planner::ForwardKinematics(composed.kinematics().arm, q);
    const Eigen::Isometry3d b = planner::ForwardKinematics(file.kinematics().arm, q);
    EXPECT_LT((a.matrix() - b.matrix()).norm(), 1e-9) << c.name;
  }
}

TEST(PositionerTypes, PresetsCarryTheirTypeAndTheScenarioOverridesIt) {
  EXPECT_EQ(PresetInfo(CellPreset::kKukaKr16Turntable).positioner, PositionerType::kTurntable);
  EXPECT_EQ(PresetInfo(CellPreset::kAbbIrb1600Table).positioner, PositionerType::kNone);
  EXPECT_EQ(PresetInfo(CellPreset::kKukaKr16).positioner, PositionerType::kTiltRotate);
  const fs::path dir = fs::temp_directory_path() / ("waam_positioner_types_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "s.yaml";
  std::ofstream(file) << "name: s\ncell:\n  preset: kuka_kr16_turntable\n  positioner: {type: none}\n";
  YamlMap top = YamlMap(LoadYamlFile(file.string()), "", file.string());
  const CellSettings settings = ParseCellSection(top);
  ASSERT_TRUE(settings.positioner_type.has_value());
  EXPECT_EQ(*settings.positioner_type, PositionerType::kNone);
  EXPECT_EQ(LoadCell(settings).kinematics().positioner.type, PositionerType::kNone);
  fs::remove_all(dir);
}

class PositionerBadInputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("waam_positioner_bad_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string ErrorOf(const std::string& yaml) {
    const fs::path file = dir_ / "bad.yaml";
    std::ofstream(file) << yaml;
    try {
      YamlMap top = YamlMap(LoadYamlFile(file.string()), "", file.string());
      LoadCell(ParseCellSection(top));
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "expected an InputError for:\n" << yaml;
    return "";
  }
  fs::path dir_;
};

TEST_F(PositionerBadInputTest, UnknownTypeIsNamedWithTheChoices) {
  const std::string message = ErrorOf("name: s\ncell:\n  positioner:\n    type: rotary\n");
  EXPECT_THAT(message, HasSubstr("bad.yaml:4"));
  EXPECT_THAT(message, HasSubstr("rotary"));
  EXPECT_THAT(message, HasSubstr("none, turntable, tilt_rotate"));
  EXPECT_EQ(message.find('\n'), std::string::npos) << "one line";
}

TEST_F(PositionerBadInputTest, TypeOtherThanTheModelFilesIsAnError) {
  const std::string message =
      ErrorOf("name: s\ncell:\n  mjcf: " + analysis::BuiltinCellPath().string() + "\n  positioner: {type: turntable}\n");
  EXPECT_THAT(message, HasSubstr("cell.positioner.type is turntable"));
  EXPECT_THAT(message, HasSubstr("tilt_rotate"));
}

}  // namespace positioner_types_test
}  // namespace waam::twin
