// Tests of the scenario's field tables: the generated key docs, the --set key paths, and validation in code.
#include "analysis/scenario_keys.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace waam::analysis
