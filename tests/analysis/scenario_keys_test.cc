// Tests of the scenario's field tables: the generated key docs, the --set key paths, and validation in code.
#include "analysis/scenario_keys.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/place_command.h"
#include "models/core/error.h"
#include "twin/cell/cell_settings.h"

namespace waam::analysis {
namespace {
using ::testing::HasSubstr;

TEST(ScenarioKeys, CommittedDocsMatchTheFieldTables) {
  std::ifstream in(std::filesystem::path(WAAM_SOURCE_DIR) / "docs/SCENARIO_KEYS.md");
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), ScenarioKeysMarkdown())
      << "docs/SCENARIO_KEYS.md differs from the field tables: run `waam scenario-keys > docs/SCENARIO_KEYS.md`";
}

TEST(ScenarioKeys, DocsCarryUnitDefaultAndRange) {
  const std::string md = ScenarioKeysMarkdown();
  EXPECT_THAT(md, HasSubstr("| `voxel_mm` | number | mm | 0.5 | [0.1, 2] |"));
  EXPECT_THAT(md, HasSubstr("| `rotation_deg` | number | deg | 0 | [-240, 240] |"));
  EXPECT_THAT(md, HasSubstr("| `blend` | name |  | speed | none, fixed, speed |"));
}

TEST(ScenarioKeys, KeyPathsOfEverySection) {
  for (const char* key : {"name", "path.bead_width_mm", "cell.torch.tcp_mm", "cell.positioner.rotation_deg",
                          "part.generator.height_mm", "simulation.voxel_mm", "path.void_filling.mode", "cell",
                          "program.gcode.arc_on_m", "run.expected_exit_code", "place.table_rotation_deg"}) {
    EXPECT_TRUE(IsScenarioKeyPath(key)) << key;
  }
  for (const char* key : {"path.bead_widht_mm", "cell.torch.tcp", "nosuch", "simulation.voxel_mm.x", ""}) {
    EXPECT_FALSE(IsScenarioKeyPath(key)) << key;
  }
}

TEST(ScenarioKeys, AnOverrideOfAnUnknownKeyNamesTheSectionsKeys) {
  EXPECT_NO_THROW(CheckOverrideKeys({"path.pattern=zigzag", "cell.positioner.rotation_deg=30"}));
  try {
    CheckOverrideKeys({"path.bead_widht_mm=5"});
    FAIL() << "expected InputError for a misspelt key";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("--set 'path.bead_widht_mm=5': unknown key 'path.bead_widht_mm'"));
    EXPECT_THAT(e.what(), HasSubstr("keys of path: pattern bead_width_mm"));
  }
}

TEST(ScenarioKeys, CellSettingsBuiltInCodeAreCheckedAgainstTheKeysLimits) {
  twin::CellSettings cell;
  EXPECT_NO_THROW(twin::ValidateCellSettings(cell));
  cell.positioner_rotation_deg = 300.0;
  try {
    twin::ValidateCellSettings(cell);
    FAIL() << "expected InputError past the table's rotation limit";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cell.positioner.rotation_deg = 300: must be in [-240, 240]"));
  }
  Scenario scenario;
  scenario.cell.torch.tcp_mm = {0.0, 0.0, 20.0};
  EXPECT_THROW(ValidateScenario(scenario), InputError);
}

std::string ValidationError(const Scenario& scenario) {
  try {
    ValidateScenario(scenario);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ScenarioKeys, ListsKeyedMapsAndGeneratorsBuiltInCodeAreCheckedByTheirTables) {
  EXPECT_EQ(ValidationError(Scenario{}), "(no error)");
  Scenario s;
  s.slicing.sub_volumes.push_back({"a", {0.0, 0.0, 1.0}, {{0.0, 0.0, 1.0, 10.0}}});
  EXPECT_EQ(ValidationError(s), "(no error)");
  s.slicing.sub_volumes.push_back({"b", {0.0, 0.0, 2000.0}, {}});
  EXPECT_THAT(ValidationError(s), HasSubstr("slicing.sub_volumes[1].direction = 2000: must be in [-1000, 1000]"));
  s = Scenario{};
  s.slicing.sub_volumes.push_back({"a", {0.0, 0.0, 1.0}, {{0.0, 0.0, 1.0, 2e6}}});
  EXPECT_THAT(ValidationError(s), HasSubstr("slicing.sub_volumes[0].keep = 2e+06: must be in [-1e+06, 1e+06]"));
  s = Scenario{};
  s.program.frames.uframe[1000] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  EXPECT_THAT(ValidationError(s), HasSubstr("program.frames.uframe.1000: must be a frame number in [1, 999]"));
  s = Scenario{};
  s.program.frames.utool[5] = std::nullopt;  // the torch
  s.program.frames.utool[6] = std::array<double, 6>{0.0, 0.0, 3e6, 0.0, 0.0, 0.0};
  EXPECT_THAT(ValidationError(s), HasSubstr("program.frames.utool.6 = 3e+06: must be in [-1e+06, 1e+06]"));
  s = Scenario{};
  s.part.generator = planner::PartGenerator::kBox;
  s.part.params = {{"size_mm", {100.0, 60.0, 40.0}}};
  EXPECT_EQ(ValidationError(s), "(no error)");
  s.part.params = {{"size_mm", {1.0, 2.0}}};
  EXPECT_THAT(ValidationError(s), HasSubstr("part.generator: box.size_mm = [1, 2]: needs 3 values"));
  s.part.params = {{"radius_mm", {1.0}}};
  EXPECT_THAT(ValidationError(s), HasSubstr("part.generator: unknown parameter 'radius_mm' for generator box"));
}

// The rows of ranges, word lists and optional names check settings built in code as the parser checks the file.
TEST(ScenarioKeys, RangesWordListsAndCellRowsBuiltInCodeAreCheckedByTheirTables) {
  Scenario s;
  s.place.table_rotation_deg = PlaceRange{0.0, 120.0, 30.0};
  EXPECT_EQ(ValidationError(s), "(no error)");
  s.place.table_rotation_deg = PlaceRange{0.0, 300.0, 30.0};
  EXPECT_THAT(ValidationError(s), HasSubstr("place.table_rotation_deg = 300: must be in [-240, 240]"));
  s.place.table_rotation_deg = PlaceRange{10.0, -10.0, 5.0};
  EXPECT_THAT(ValidationError(s), HasSubstr("place.table_rotation_deg = [10, -10, 5]: min must not exceed max"));
  s.place.table_rotation_deg = PlaceRange{-10.0, 10.0, 0.0};
  EXPECT_THAT(ValidationError(s), HasSubstr("place.table_rotation_deg: step 0 with min < max"));
  s = Scenario{};
  s.place.part_x_mm = s.place.part_y_mm = s.place.part_yaw_deg = PlaceRange{-100.0, 100.0, 0.5};
  EXPECT_THAT(ValidationError(s), HasSubstr("place: the ranges give more than 20000 layouts"));
  s = Scenario{};
  s.place.part_x_mm = PlaceRange{-20.0, 20.0, 1e-300};  // 4e301 values: a count no integer type holds
  EXPECT_THAT(ValidationError(s), HasSubstr("place: the ranges give more than 20000 layouts"));
  s = Scenario{};
  s.cell.robot_joints = {"a", "b"};
  EXPECT_THAT(ValidationError(s), HasSubstr("cell.robot.joints: must list 6 joints, got 2"));
  s = Scenario{};
  s.cell.axis_ramp_s = 50.0;
  EXPECT_THAT(ValidationError(s), HasSubstr("cell.axis_ramp_s = 50: must be in [0.01, 10]"));
  s = Scenario{};
  s.program.gcode_arc_on = {"M62 P1"};
  EXPECT_EQ(ValidationError(s), "(no error)");
  s.program.gcode_arc_on = {"X3"};
  EXPECT_THAT(ValidationError(s), HasSubstr("program.gcode.arc_on 'X3': an arc signal is a G or M code"));
  const std::string md = ScenarioKeysMarkdown();
  EXPECT_THAT(md, HasSubstr("| `format` | name |  | auto | auto, "));
  EXPECT_THAT(md, HasSubstr("| `table_rotation_deg` | list of numbers | deg |  | [-240, 240] |"));
  EXPECT_THAT(md, HasSubstr("| `joints` | list |  |  |  |"));
}

TEST(ScenarioKeys, GeneratorParametersFramesAndSubVolumesHaveKeyPaths) {
  for (const char* key : {"part.generator.type", "part.generator.size_mm", "part.generator.arm_angles_deg",
                          "program.frames.uframe.6", "program.frames.utool", "slicing.sub_volumes"}) {
    EXPECT_TRUE(IsScenarioKeyPath(key)) << key;
  }
  for (const char* key : {"part.generator.sizes_mm", "program.frames.tool.6"}) {
    EXPECT_FALSE(IsScenarioKeyPath(key)) << key;
  }
  const std::string md = ScenarioKeysMarkdown();
  EXPECT_THAT(md, HasSubstr("## `part.generator` (type: box)"));
  EXPECT_THAT(md, HasSubstr("| `size_mm` | list of numbers | mm | [100, 60, 40] | [0.1, 5000] |"));
  EXPECT_THAT(md, HasSubstr("| `utool` | mapping | mm, deg |  | tool 1-999: [-1000000, 1000000] or torch |"));
}

TEST(ScenarioKeys, APlacedLayoutOutOfTheCellsLimitsIsRefusedNamingTheKey) {
  const twin::CellSettings cell;
  Layout layout{};
  layout[kTableRotation] = 120.0;
  EXPECT_NO_THROW(ApplyLayout(cell, layout));
  layout[kTableRotation] = 300.0;
  try {
    ApplyLayout(cell, layout);
    FAIL() << "expected InputError for a table rotation past the cell's limit";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cell.positioner.rotation_deg = 300: must be in [-240, 240]"));
  }
}

}  // namespace
}  // namespace waam::analysis
