// Tests of the scenario's optional `cell:` section: defaults, values, and refused keys and ranges.
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "analysis/scenario.h"

namespace waam::planner {
namespace {
// The twin's settings types (these tests read whole scenario files, analysis::LoadScenario).
using twin::CellSettings;
namespace fs = std::filesystem;
using ::testing::HasSubstr;

class CellSectionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("waam_cell_section_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    std::ofstream(dir_ / "my_cell.xml") << "<mujoco/>\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path Write(const std::string& cell) {
    const fs::path file = dir_ / "s.yaml";
    std::ofstream(file) << "name: demo\npart:\n  generator: {type: box, size_mm: [40, 30, 10]}\n"
                           "slicing:\n  layer_height_mm: 1.5\npath:\n  pattern: zigzag\n  bead_width_mm: 6\n"
                           "process:\n  travel_speed_mm_min: 400\n  wire_feed_mm_min: 3200\n"
                        << cell;
    return file;
  }
  std::string ErrorOf(const std::string& cell) {
    try {
      analysis::LoadScenario(Write(cell));
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "expected an InputError for:\n" << cell;
    return "";
  }
  fs::path dir_;
};

TEST_F(CellSectionTest, AbsentSectionGivesDefaults) {
  const analysis::Scenario s = analysis::LoadScenario(Write(""));
  EXPECT_TRUE(s.cell.mjcf.empty());
  EXPECT_DOUBLE_EQ(s.cell.positioner_base_mm[0], CellSettings{}.positioner_base_mm[0]);
  EXPECT_DOUBLE_EQ(s.cell.joint_margin_deg, 2.0);
}

TEST_F(CellSectionTest, ValuesAreRead) {
  const analysis::Scenario s = analysis::LoadScenario(Write(
      "cell:\n  mjcf: my_cell.xml\n  robot: {base_mm: [10, 20, 30], yaw_deg: 15}\n"
      "  positioner: {base_mm: [900, 5, 0], yaw_deg: 0, rotation_deg: 45, follow: point}\n"
      "  part: {offset_mm: [1, 2, 3], yaw_deg: 30}\n"
      "  checks: {joint_margin_deg: 3, singularity_deg: 8, step_mm: 2, collision_tolerance_mm: 0.5, "
      "part_collision: false}\n"));
  EXPECT_EQ(s.cell.mjcf, (dir_ / "my_cell.xml").lexically_normal());
  EXPECT_DOUBLE_EQ(s.cell.robot_base_mm[2], 30.0);
  EXPECT_DOUBLE_EQ(s.cell.robot_yaw_deg, 15.0);
  EXPECT_DOUBLE_EQ(s.cell.positioner_base_mm[0], 900.0);
  EXPECT_DOUBLE_EQ(s.cell.positioner_rotation_deg, 45.0);
  EXPECT_EQ(NameOf(s.cell.positioner_follow), "point");
  EXPECT_DOUBLE_EQ(s.cell.part_offset_mm[1], 2.0);
  EXPECT_DOUBLE_EQ(s.cell.part_yaw_deg, 30.0);
  EXPECT_DOUBLE_EQ(s.cell.joint_margin_deg, 3.0);
  EXPECT_DOUBLE_EQ(s.cell.singularity_deg, 8.0);
  EXPECT_DOUBLE_EQ(s.cell.step_mm, 2.0);
  EXPECT_DOUBLE_EQ(s.cell.collision_tolerance_mm, 0.5);
  EXPECT_FALSE(s.cell.part_collision);
}

TEST_F(CellSectionTest, BadInputNamesTheKey) {
  EXPECT_THAT(ErrorOf("cell:\n  mjcf: missing.xml\n"), HasSubstr("cell.mjcf"));
  EXPECT_THAT(ErrorOf("cell:\n  mjcf: missing.xml\n"), HasSubstr("not found"));
  EXPECT_THAT(ErrorOf("cell:\n  robot: {base_mm: [1, 2]}\n"), HasSubstr("cell.robot.base_mm"));
  EXPECT_THAT(ErrorOf("cell:\n  checks: {step_mm: 0}\n"), HasSubstr("cell.checks.step_mm"));
  EXPECT_THAT(ErrorOf("cell:\n  robots: {}\n"), HasSubstr("robots"));
  EXPECT_THAT(ErrorOf("cell:\n  positioner: {follow: always}\n"), HasSubstr("cell.positioner.follow"));
  EXPECT_THAT(ErrorOf("cell:\n  positioner: {tilt_deg: 3}\n"), HasSubstr("tilt_deg"));
}

TEST_F(CellSectionTest, UrdfArmKeysAreRead) {
  std::ofstream(dir_ / "arm.urdf") << "<robot name=\"a\"/>\n";
  const analysis::Scenario s = analysis::LoadScenario(Write(
      "cell:\n  robot:\n    urdf: arm.urdf\n    package_paths: [pkgs, /opt/ros]\n"
      "    joints: [a1, a2, a3, a4, a5, a6]\n    flange: flange\n    base_mm: [0, 0, 100]\n"
      "  torch: {tcp_mm: [0, 30, 380], nozzle_radius_mm: 9, nozzle_length_mm: 50}\n"));
  EXPECT_EQ(s.cell.robot_urdf, (dir_ / "arm.urdf").lexically_normal());
  ASSERT_EQ(s.cell.robot_package_paths.size(), 2u);
  EXPECT_EQ(s.cell.robot_package_paths[0], (dir_ / "pkgs").lexically_normal());
  EXPECT_EQ(s.cell.robot_package_paths[1], fs::path("/opt/ros"));
  EXPECT_EQ(s.cell.robot_joints.size(), 6u);
  EXPECT_EQ(s.cell.robot_flange, "flange");
  EXPECT_DOUBLE_EQ(s.cell.torch.tcp_mm[1], 30.0);
  EXPECT_DOUBLE_EQ(s.cell.torch.nozzle_radius_mm, 9.0);
  EXPECT_DOUBLE_EQ(s.cell.robot_base_mm[2], 100.0);
}

TEST_F(CellSectionTest, UrdfArmKeysAreChecked) {
  std::ofstream(dir_ / "arm.urdf") << "<robot name=\"a\"/>\n";
  EXPECT_THAT(ErrorOf("cell:\n  robot: {urdf: none.urdf}\n"), HasSubstr("cell.robot.urdf: URDF file"));
  EXPECT_THAT(ErrorOf("cell:\n  mjcf: my_cell.xml\n  robot: {urdf: arm.urdf}\n"),
              HasSubstr("give cell.mjcf or cell.robot.urdf, not both"));
  EXPECT_THAT(ErrorOf("cell:\n  robot: {urdf: arm.urdf, joints: [a, b]}\n"), HasSubstr("cell.robot.joints: must list 6 joints, got 2"));
  EXPECT_THAT(ErrorOf("cell:\n  torch: {tcp_mm: [0, 0, 10]}\n"), HasSubstr("at least 50 mm"));
  EXPECT_THAT(ErrorOf("cell:\n  torch: {tcp_mm: [0, 0, 100], nozzle_length_mm: 90}\n"),
              HasSubstr("shorter than the torch"));
  EXPECT_THAT(ErrorOf("cell:\n  torch: {tcp: 3}\n"), HasSubstr("tcp"));
}

}  // namespace
}  // namespace waam::planner
