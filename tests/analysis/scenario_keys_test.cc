// Tests of the scenario's field tables: the generated key docs, the --set key paths, and validation in code.
#include "analysis/scenario_keys.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/bench_command.h"
#include "analysis/place_command.h"
#include "analysis/scenario.h"
#include "analysis/sweep.h"
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

// Writes `text` as s.yaml (with an empty log.csv beside it for a replay: section) in a per-process folder.
std::filesystem::path WriteKeysScenario(const std::string& text) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("waam_scenario_keys_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "s.yaml") << text;
  std::ofstream(dir / "log.csv") << "";
  return dir / "s.yaml";
}

// The message LoadScenario refuses `file` with (and `overrides`), which must be one line.
std::string LoadError(const std::filesystem::path& file, const std::vector<std::string>& overrides = {}) {
  try {
    (void)LoadScenario(file, overrides);
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
    return what;
  }
  return "(no error)";
}

// A thermal scenario with a replay: section; lines 11-15 thermal, 16-21 replay.
std::string ReplayScenarioText() {
  return "name: r\n"
         "part:\n  generator: {type: box, size_mm: [40, 6, 4]}\n"
         "slicing: {layer_height_mm: 2}\npath: {pattern: zigzag, bead_width_mm: 6}\n"
         "process:\n  travel_speed_mm_min: 480\n  wire_feed_mm_min: 3200\n  arc: {power_w: 2000}\n"
         "  interpass: {max_c: 200, at: {probe: plate}}\n"
         "thermal:\n  material: mild_steel\n  substrate: {size_mm: [70, 30, 6], material: ss316l}\n"
         "  probes: {plate: [0, 10, -2]}\n  table: {conductance_w_m2k: 500, thickness_mm: 20}\n"
         "replay:\n  log: log.csv\n  columns: {power_w: P}\n  ambient_column: Tair\n"
         "  probes:\n    near: {column: T1, at_mm: [0, 7, -1]}\n";
}

// The keys once read by hand (replay's extra columns and thermocouples, thermal's probes and materials, interpass.at,
// part.generator.type) are rows of their tables: read, documented, reached by --set and checked in code.
TEST(ScenarioKeys, ProbesMaterialsColumnsAndInterpassAtAreRowsOfTheirTables) {
  const std::filesystem::path file = WriteKeysScenario(ReplayScenarioText());
  const Scenario s = LoadScenario(file, {"replay.table_column=Ttable", "thermal.probes.plate=[0, 12, -2]"});
  EXPECT_EQ(s.replay.columns.ambient, "Tair");
  EXPECT_EQ(s.replay.columns.table, "Ttable") << "--set reaches replay.table_column";
  ASSERT_EQ(s.replay.probes.size(), 1u);
  EXPECT_EQ(s.replay.probes[0].column, "T1");
  EXPECT_EQ(s.replay.probes[0].at_mm, Eigen::Vector3d(0, 7, -1));
  EXPECT_THAT(s.replay.probes[0].where, HasSubstr("s.yaml:21: replay.probes.near.at_mm"));
  ASSERT_EQ(s.thermal.probes.size(), 1u);
  EXPECT_EQ(s.thermal.probes[0].p_mm, Eigen::Vector3d(0, 12, -2)) << "--set reaches thermal.probes.NAME";
  EXPECT_EQ(s.thermal.substrate.name_or_path, "ss316l");
  EXPECT_EQ(s.process.interpass.at, planner::InterpassAt::kProbe);
  EXPECT_EQ(s.process.interpass.probe, "plate");
  EXPECT_EQ(s.part.generator, planner::PartGenerator::kBox);
  for (const char* key : {"replay.ambient_column", "replay.table_column", "replay.probes.near.at_mm",
                          "thermal.probes.plate", "thermal.material", "thermal.substrate.material",
                          "thermal.shape.bead_model", "process.interpass.at", "part.generator.type"}) {
    EXPECT_TRUE(IsScenarioKeyPath(key)) << key;
  }
  const std::string md = ScenarioKeysMarkdown();
  EXPECT_THAT(md, HasSubstr("## `replay.probes.<NAME>`"));
  EXPECT_THAT(md, HasSubstr("| `at_mm` | list of numbers | mm | [0, 0, 0] | [-100000, 100000] |"));
  EXPECT_THAT(md, HasSubstr("| `probes` | mapping | mm |  | [-10000, 10000] | NAME: [x, y, z] in the part frame |"));
  EXPECT_THAT(md, HasSubstr("| `at` | name |  | next_start | next_start, top_max, probe |"));
  EXPECT_THAT(md, HasSubstr("| `type` | name |  |  | bent_tube, box,"));
  EXPECT_THAT(md, HasSubstr("| `ambient_column` | string |"));
}

// A --set value or a value set in code outside a moved key's range is refused on one line naming the key.
TEST(ScenarioKeys, OutOfRangeValuesOfTheMovedKeysAreRefusedFromSetAndFromCode) {
  const std::filesystem::path file = WriteKeysScenario(ReplayScenarioText());
  EXPECT_THAT(LoadError(file, {"replay.probes.near.at_mm=[0, 7, 2e5]"}),
              HasSubstr("replay.probes.near.at_mm[2] = 200000: must be in [-100000, 100000]"));
  EXPECT_THAT(LoadError(file, {"thermal.probes.plate=[0, 2e4, 0]"}),
              HasSubstr("thermal.probes.plate[1] = 20000: must be in [-10000, 10000]"));
  EXPECT_THAT(LoadError(file, {"process.interpass.at=probe"}),
              HasSubstr("process.interpass.at = probe: name the probe, as at: {probe: NAME}"));
  EXPECT_THAT(LoadError(file, {"part.generator.type=blob"}),
              HasSubstr("part.generator: unknown generator type 'blob' (known: bent_tube, box"));
  EXPECT_THAT(LoadError(file, {"replay.probes.near.colum=T1"}), HasSubstr("replay.probes.near.colum: unknown key"));
  Scenario s = LoadScenario(file);
  EXPECT_EQ(ValidationError(s), "(no error)");
  s.replay.probes[0].at_mm.z() = 2e5;
  EXPECT_THAT(ValidationError(s), HasSubstr("replay.probes.near.at_mm = 200000: must be in [-100000, 100000]"));
  s = LoadScenario(file);
  s.thermal.probes[0].p_mm.y() = 2e4;
  EXPECT_THAT(ValidationError(s), HasSubstr("thermal.probes.plate = 20000: must be in [-10000, 10000]"));
  s = LoadScenario(file);
  s.thermal.table_conductance_w_m2k = 0.0;
  EXPECT_THAT(ValidationError(s), HasSubstr("thermal.table.conductance_w_m2k = 0 with thickness_mm = 20: a table "
                                            "body needs a contact conductance > 0"));
  s = LoadScenario(file);
  s.run.expected_exit_code = 2;
  EXPECT_THAT(ValidationError(s), HasSubstr("run.expected_exit_code = 2: must be 0 (success) or 3"));
  s = LoadScenario(file);
  s.program.gcode_arc_off_m = s.program.gcode_arc_on_m;
  EXPECT_THAT(ValidationError(s), HasSubstr("program.gcode.arc_off_m = 3: must differ from arc_on_m"));
  s = LoadScenario(file);
  s.process.interpass.probe.clear();
  EXPECT_THAT(ValidationError(s), HasSubstr("process.interpass.at = probe: name the probe"));
  // The rules across slicing keys hold for settings built in code too.
  s = LoadScenario(file);
  s.slicing.type = planner::SlicingType::kSkeleton;
  s.slicing.h_min_mm = 3.0;
  s.slicing.h_max_mm = 2.0;
  EXPECT_THAT(ValidationError(s), HasSubstr("slicing.h_max_mm = 2: must be >= slicing.h_min_mm = 3"));
  s = LoadScenario(file);
  s.slicing.type = planner::SlicingType::kCone;
  s.slicing.cone_H_mm = 0.5;
  EXPECT_THAT(ValidationError(s), HasSubstr("slicing.H_mm = 0.5: |H| must be >= 1 mm"));
}

// A sweep over a moved key: the run whose value is outside the key's range is refused before any run, on one line.
TEST(ScenarioKeys, ASweepValueOutsideAMovedKeysRangeIsRefusedBeforeAnyRun) {
  const std::filesystem::path file = WriteKeysScenario(ReplayScenarioText());
  const Sweep sweep = ParseSweep("base: " + file.string() + "\ngrid:\n  thermal.probes.plate: [[0, 10, -2], [0, 2e4, 0]]\n",
                                 file.parent_path() / "sweep.yaml");
  ASSERT_EQ(sweep.runs.size(), 2u);
  try {
    CheckBenchOverrides(SweepBenchRuns(sweep), BenchOptions{});
    FAIL() << "expected the second run's probe to be refused";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_THAT(what, HasSubstr("run " + sweep.runs[1].id + ": "));
    EXPECT_THAT(what, HasSubstr("thermal.probes.plate[1] = 20000: must be in [-10000, 10000]"));
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
  }
}

// program.yaskawa's pulses have no default: absent is unknown; a zero given is refused where it is written.
TEST(ScenarioKeys, PulsesPerDegreeAbsentAreUnknownAndAZeroGivenIsRefused) {
  const std::string text =
      "name: j\nprogram:\n  file: j.JBI\n  yaskawa:\n    pulses_per_deg: [1000, 1400, 1000, 800, 1200, 500]\n"
      "process: {travel_speed_mm_min: 400, wire_feed_mm_min: 3200}\n";
  const std::filesystem::path file = WriteKeysScenario(text);
  EXPECT_THAT(LoadError(file, {"program.yaskawa.station_pulses_per_deg=[0, 1000]"}),
              HasSubstr("program.yaskawa.station_pulses_per_deg[0] = 0: must be in [0.001, 1e+07]"));
  std::string zero = text;
  zero.replace(zero.find("[1000, 1400"), 5, "[0");
  EXPECT_THAT(LoadError(WriteKeysScenario(zero)),
              HasSubstr("s.yaml:5: program.yaskawa.pulses_per_deg[0] = 0: must be in [0.001, 1e+07]"));
  Scenario s;
  EXPECT_FALSE(s.program.yaskawa_pulses_per_deg.has_value()) << "absent: unknown, not zeros";
  s.program.yaskawa_station_pulses_per_deg = std::array<double, 2>{0.0, 1000.0};
  EXPECT_THAT(ValidationError(s), HasSubstr("program.yaskawa.station_pulses_per_deg = 0: must be in [0.001, 1e+07]"));
  const std::string md = ScenarioKeysMarkdown();
  EXPECT_THAT(md, HasSubstr("| `pulses_per_deg` | list of numbers |  |  | [0.001, 10000000] | the arm's encoder"));
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
