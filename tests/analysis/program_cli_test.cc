// Tests of `waam import`, `waam export` and a scenario's program: section through the CLI: a scenario exported in
// every dialect imports back to the plan `waam plan` makes of it, check runs on a program scenario, and a bad
// program exits 2 writing nothing.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/import_command.h"
#include "analysis/program_file.h"
#include "analysis/plan_command.h"
#include "cli_test_util.h"
#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using cli_test::ReadJson;
using cli_test::RunWaam;
using cli_test::TempDir;
using cli_test::Slurp;

fs::path ProgramFixture(const char* name) {
  return fs::path(WAAM_SOURCE_DIR) / "tests" / "data" / "programs" / name;
}

TEST(ProgramCliTest, ExportThenImportGivesThePlanOfTheScenario) {
  const fs::path dir = TempDir("program_export_import");
  const fs::path scenario = fs::path(WAAM_SOURCE_DIR) / "scenarios" / "box.yaml";
  std::string err;
  ASSERT_EQ(RunWaam("plan " + scenario.string() + " -o " + (dir / "plan").string() + " -q --no-images", &err), 0)
      << err;
  const nlohmann::json planned = ReadJson(dir / "plan" / "plan.json");
  for (const char* f : {"box.ls", "box.mod", "box.src", "box.nc", "box.csv", "box.JBI"}) {
    SCOPED_TRACE(f);
    const fs::path program = dir / f;
    // A JBI's station positions are encoder pulses: written and read with the same pulses per degree.
    const std::string pulses = fs::path(f).extension() == ".JBI" ? " --station-pulses-per-deg 1365.3,1137.8" : "";
    ASSERT_EQ(RunWaam("export " + scenario.string() + " -o " + program.string() + pulses + " -q", &err), 0) << err;
    const fs::path out = dir / (std::string("import_") + f);
    ASSERT_EQ(RunWaam("import " + program.string() + " --scenario " + scenario.string() + " -o " + out.string() +
                          pulses + " -q --no-images",
                      &err),
              0)
        << err;
    const nlohmann::json imported = ReadJson(out / "plan.json");
    for (const char* key : {"layers", "passes", "path_elements"}) {
      EXPECT_EQ(imported[key], planned[key]) << key;
    }
    EXPECT_NEAR(imported["weld_length_mm"].get<double>(), planned["weld_length_mm"].get<double>(), 0.01);
    EXPECT_TRUE(imported["import"]["warnings"].empty());
    EXPECT_TRUE(fs::exists(out / "plan.h5"));
  }
}

TEST(ProgramCliTest, CheckAndPlanAcceptAProgramScenario) {
  const fs::path dir = TempDir("program_scenario");
  std::string err;
  ASSERT_EQ(RunWaam("check " + ProgramFixture("wall_ls.yaml").string() + " -o " + (dir / "check").string() +
                        " -q --no-images",
                    &err),
            0)
      << err;
  EXPECT_THAT(err, HasSubstr("instruction CALL not executed (1x, first at line 27)"));
  const nlohmann::json check = ReadJson(dir / "check" / "check.json");
  EXPECT_EQ(check["points"], 41);
  ASSERT_EQ(RunWaam("plan " + ProgramFixture("wall_mod.yaml").string() + " -o " + (dir / "plan").string() +
                        " -q --no-images",
                    &err),
            0)
      << err;
  const nlohmann::json plan = ReadJson(dir / "plan" / "plan.json");
  EXPECT_EQ(plan["layers"], 2);
  EXPECT_EQ(plan["import"]["format"], "abb_rapid");
}

TEST(ProgramCliTest, ExportWritesThePresetsDialectAndAJbiScenarioPlans) {
  const fs::path dir = TempDir("program_preset_dialect");
  const fs::path scenario = fs::path(WAAM_SOURCE_DIR) / "scenarios" / "cell" / "preset_yaskawa_mh12.yaml";
  std::string err;
  // No --format and no extension: the Yaskawa preset's dialect, which needs the station's pulses per degree.
  EXPECT_EQ(RunWaam("export " + scenario.string() + " -o " + (dir / "job").string() + " -q", &err), 2);
  EXPECT_THAT(err, HasSubstr("station's pulses per degree"));
  EXPECT_FALSE(fs::exists(dir / "job"));
  ASSERT_EQ(RunWaam("export " + scenario.string() + " -o " + (dir / "job").string() +
                        " --station-pulses-per-deg 1000,1000 -q",
                    &err),
            0)
      << err;
  const std::string job = ReadFile(dir / "job");
  EXPECT_EQ(job.substr(0, 5), "/JOB\n");
  EXPECT_THAT(job, HasSubstr("///GROUP1 RB1,ST1"));
  // A scenario whose program: is a JBI with a pulse position (its pulses per degree in program.yaskawa).
  ASSERT_EQ(RunWaam("plan " + ProgramFixture("wall_jbi.yaml").string() + " -o " + (dir / "plan").string() +
                        " -q --no-images",
                    &err),
            0)
      << err;
  const nlohmann::json plan = ReadJson(dir / "plan" / "plan.json");
  EXPECT_EQ(plan["layers"], 2);
  EXPECT_EQ(plan["import"]["format"], "yaskawa_jbi");
}

TEST(ProgramCliTest, ProgramSectionIsCheckedWhereItIsWritten) {
  const fs::path dir = TempDir("program_section");
  fs::copy_file(ProgramFixture("wall.nc"), dir / "wall.nc");
  auto error = [&](const std::string& yaml) {
    WriteFileAtomic(dir / "s.yaml", yaml);
    try {
      (void)LoadScenario(dir / "s.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string process = "process: {travel_speed_mm_min: 400, wire_feed_mm_min: 3200}\n";
  EXPECT_THAT(error("name: s\nprogram:\n  file: wall.nc\n  format: fanuc\n" + process),
              HasSubstr("s.yaml:4: program.format = 'fanuc': must be auto or one of csv, fanuc_ls"));
  EXPECT_THAT(error("name: s\nprogram:\n  file: nowhere.ls\n" + process), HasSubstr("program file"));
  EXPECT_THAT(error("name: s\npart: {mesh: wall.nc}\nprogram:\n  file: wall.nc\n" + process),
              HasSubstr("give either part (planned here) or program (planned elsewhere), not both"));
  EXPECT_THAT(error("name: s\nprogram:\n  file: wall.nc\n  frame: {user_frame_mm: [0, 0, 0]}\n" + process),
              HasSubstr("program.frame.user_frame_mm"));
  EXPECT_EQ(error("name: s\nprogram:\n  file: wall.nc\n  gcode: {arc_on_m: 7, arc_off_m: 9}\n" + process),
            "no error");
  // program.gcode.feed_unit and program.frames (numbered frames and tools, a tool may be the cell's torch).
  EXPECT_EQ(error("name: s\nprogram:\n  file: wall.nc\n  gcode: {feed_unit: mm_per_s}\n  frames: {uframe: {2: [0, 0, "
                  "0, 0, 0, 90]}, utool: {1: torch, 3: [0, 0, 400, 0, 0, 0]}}\n" + process),
            "no error");
  EXPECT_EQ(error("name: s\nprogram:\n  file: wall.nc\n  gcode: {arc_on: [M62 P1, G82], arc_off: [M63 P1], "
                  "dwell_p_unit: s}\n" + process),
            "no error");
  EXPECT_THAT(error("name: s\nprogram:\n  file: wall.nc\n  gcode: {dwell_p_unit: minutes}\n" + process),
              HasSubstr("program.gcode.dwell_p_unit = 'minutes'"));
  EXPECT_THAT(error("name: s\nprogram:\n  file: wall.nc\n  gcode: {arc_off: []}\n" + process),
              HasSubstr("program.gcode.arc_off: must list at least one signal"));
  EXPECT_THAT(error("name: s\nprogram:\n  file: wall.nc\n  gcode: {feed_unit: mm_per_hour}\n" + process),
              HasSubstr("program.gcode.feed_unit = 'mm_per_hour'"));
  EXPECT_THAT(error("name: s\nprogram:\n  file: wall.nc\n  frames: {uframe: {six: [0, 0, 0, 0, 0, 0]}}\n" + process),
              HasSubstr("program.frames.uframe.six: must be a frame number in [1, 999]"));
  EXPECT_THAT(error("name: s\nprogram:\n  file: wall.nc\n  frames: {uframe: {6: torch}}\n" + process),
              HasSubstr("only a tool (utool) can be the cell's torch"));
  EXPECT_THAT(error("name: s\nprogram:\n  file: wall.nc\n  frames: {utool: {6: [0, 0, 400]}}\n" + process),
              HasSubstr("program.frames.utool.6"));
  EXPECT_THAT(error("name: s\nprogram:\n  file: wall.nc\ntarget: nowhere.stl\n" + process),
              HasSubstr("s.yaml:4: target: target file"));
  EXPECT_THAT(error("name: s\npart: {generator: {type: box, size_mm: [10, 10, 5]}}\nslicing: {type: planar, "
                    "layer_height_mm: 1}\npath: {pattern: contour, bead_width_mm: 6}\ntarget: wall.nc\n" + process),
              HasSubstr("only with a program: section"));
}

TEST(ProgramCliTest, CheckMovesTheToolAProgramSetsAndSaysSo) {
  // base_tool.src sets TOOL_DATA[4] (380 mm along the flange's z, turned 20 deg) and welds with it.
  const fs::path dir = TempDir("program_tool");
  for (const char* f : {"base_tool.src", "base_tool.dat"}) fs::copy_file(ProgramFixture(f), dir / f);
  WriteFileAtomic(dir / "s.yaml", "name: base_tool\nprogram:\n  file: base_tool.src\n"
                                  "process: {travel_speed_mm_min: 400, wire_feed_mm_min: 3200}\n");
  std::string err;
  const int code = RunWaam("check " + (dir / "s.yaml").string() + " -o " + (dir / "check").string() +
                               " -q --no-images",
                           &err);
  ASSERT_TRUE(code == 0 || code == 3) << err;
  const nlohmann::json check = ReadJson(dir / "check" / "check.json");
  ASSERT_TRUE(check.contains("tool")) << check.dump().substr(0, 400);
  EXPECT_EQ(check["tool"]["name"], "TOOL_DATA[4]");
  EXPECT_EQ(check["tool"]["source"], "program");
  EXPECT_TRUE(check["tool"]["differs_from_torch"].get<bool>());
}

TEST(ProgramCliTest, TargetGivesAProgramItsDeviationMeasures) {
  const fs::path dir = TempDir("program_target");
  fs::copy_file(ProgramFixture("wall.ls"), dir / "wall.ls");
  std::string err;
  ASSERT_EQ(RunWaam("generate box --param size_mm=120,20,6 -o " + (dir / "target.stl").string(), &err), 0) << err;
  const std::string base = Slurp(ProgramFixture("wall_ls.yaml"));
  WriteFileAtomic(dir / "with.yaml", base + "target: target.stl\n");
  WriteFileAtomic(dir / "without.yaml", base);
  ASSERT_EQ(RunWaam("simulate " + (dir / "with.yaml").string() + " -q --no-images -o " + (dir / "with").string(), &err),
            0) << err;
  ASSERT_EQ(RunWaam("simulate " + (dir / "without.yaml").string() + " -q --no-images -o " + (dir / "without").string(),
                    &err), 0) << err;
  const nlohmann::json with = ReadJson(dir / "with" / "simulate.json");
  const nlohmann::json without = ReadJson(dir / "without" / "simulate.json");
  EXPECT_GT(with.at("deviation").at("samples").get<int>(), 0);
  EXPECT_EQ(without.at("deviation").at("samples").get<int>(), 0);
}

TEST(ProgramCliTest, BarOnPlateGcodeTimelineHasItsArcTimesAndDwells) {
  // A bar-on-plate build's G-code with mm/s feeds and interlayer dwells (tests/data/programs/bar_on_plate.gcode),
  // planned through a scenario: each layer's arc time is its 120 mm over F8 (mm/s), the waits are the four 60 s dwells.
  const fs::path dir = TempDir("program_bar_on_plate");
  fs::copy_file(ProgramFixture("bar_on_plate.gcode"), dir / "bar_on_plate.gcode");
  WriteFileAtomic(dir / "s.yaml",
                  "name: bar\nprogram:\n  file: bar_on_plate.gcode\n  layer_tolerance_mm: 0.5\n"
                  "  gcode: {arc_on: [M3], arc_off: [M5], feed_unit: mm_per_s, dwell_p_unit: ms}\n"
                  "process: {travel_speed_mm_min: 480, wire_feed_mm_min: 3200, arc_start_s: 0, arc_end_s: 0}\n");
  std::string err;
  ASSERT_EQ(RunWaam("plan " + (dir / "s.yaml").string() + " -o " + (dir / "plan").string() + " -q --no-images", &err),
            0)
      << err;
  const nlohmann::json timeline = ReadJson(dir / "plan" / "plan.json")["timeline"];
  ASSERT_EQ(timeline["layers"].size(), 5u);
  for (const nlohmann::json& layer : timeline["layers"]) {
    EXPECT_NEAR(layer["arc_on_s"].get<double>(), 120.0 / 8.0, 1e-6) << layer.dump();
    EXPECT_NEAR(layer["end_s"].get<double>() - layer["start_s"].get<double>(), 15.0, 1e-6) << layer.dump();
  }
  EXPECT_NEAR(timeline["wait_s"].get<double>(), 4 * 60.0, 1e-6);
  EXPECT_NEAR(timeline["arc_on_s"].get<double>(), 5 * 15.0, 1e-6);
}

TEST(ProgramCliTest, WolfSyntaxGcodeRunsThroughThermalWithItsArcTimesAndDwells) {
  // ORNL's Wolf syntax (tests/data/programs/wolf_bar.gcode: M101 / M103 the arc, F in mm/s, G4 S, packed M5T2D1F0
  // words) as a scenario's program: for `waam thermal`: three layers of 124 mm at F5, dwells of 30 and 20 s after
  // the arc ends, the arc's energy all accounted for.
  const fs::path dir = TempDir("program_wolf_thermal");
  fs::copy_file(ProgramFixture("wolf_bar.gcode"), dir / "wolf_bar.gcode");
  WriteFileAtomic(dir / "s.yaml",
                  "name: wolf\nprogram:\n  file: wolf_bar.gcode\n"
                  "  gcode: {arc_on: [M101], arc_off: [M103], feed_unit: mm_per_s, dwell_p_unit: s}\n"
                  "slicing: {layer_height_mm: 2}\npath: {pattern: zigzag, bead_width_mm: 4}\n"
                  "process:\n  travel_speed_mm_min: 300\n  wire_feed_mm_min: 3000\n  arc_start_s: 0\n"
                  "  arc_end_s: 0\n  arc: {power_w: 2000, efficiency: 0.8}\n"
                  "thermal:\n  material: mild_steel\n  cell_mm: 4\n"
                  "  substrate: {size_mm: [40, 80, 6], centre_mm: [0, 0, -5]}\n"
                  "  probes: {side: [14, 0, -3]}\n");
  std::string err;
  ASSERT_EQ(RunWaam("thermal " + (dir / "s.yaml").string() + " -q --no-images -o " + (dir / "out").string(), &err), 0) << err;
  const nlohmann::json j = ReadJson(dir / "out" / "thermal.json");
  const nlohmann::json& timeline = j["timeline"];
  ASSERT_EQ(timeline["layers"].size(), 3u);
  for (const nlohmann::json& layer : timeline["layers"]) {
    EXPECT_NEAR(layer["arc_on_s"].get<double>(), 124.0 / 5.0, 1e-6) << layer.dump();
    EXPECT_NEAR(layer["end_s"].get<double>() - layer["start_s"].get<double>(), 124.0 / 5.0, 1e-6) << layer.dump();
  }
  EXPECT_NEAR(timeline["wait_s"].get<double>(), 30.0 + 20.0, 1e-6);
  EXPECT_GE(timeline["layers"][1]["start_s"].get<double>() - timeline["layers"][0]["end_s"].get<double>(), 30.0);
  EXPECT_NEAR(j["energy_balance"]["arc_energy_j"].get<double>(), 2000.0 * 3 * 124.0 / 5.0, 1e-3);
  EXPECT_LT(std::abs(j["energy_balance"]["relative_error"].get<double>()), 0.01);
  EXPECT_GT(j["probes"]["side"]["max_c"].get<double>(), 100.0) << "the plate beside the bar heats up";
}

TEST(ProgramCliTest, BadProgramExitsTwoAndWritesNothing) {
  const fs::path dir = TempDir("program_bad");
  const fs::path bad = dir / "bad.nc";
  WriteFileAtomic(bad, "G21\nG1 X1 Y2 Z3 F400\nG1 XNaN Y2\n");
  std::string err;
  EXPECT_EQ(RunWaam("import " + bad.string() + " -o " + (dir / "out").string() + " -q", &err), 2);
  EXPECT_THAT(err, HasSubstr("bad.nc:3: X 'NaN' is not a finite number"));
  EXPECT_FALSE(fs::exists(dir / "out" / "plan.json"));
  EXPECT_EQ(RunWaam("import " + bad.string() + " --format yaskawa_jbi -o " + (dir / "out").string() + " -q", &err), 2);
  EXPECT_THAT(err, HasSubstr("bad.nc:1: a JBI job starts with /JOB, not 'G21'"));
  EXPECT_FALSE(fs::exists(dir / "out" / "plan.json"));
}

// analysis::ReadProgramFile checks the size before it reads.
TEST(ProgramFile, FilesPastTheSizeLimitAreRefusedBeforeReading) {
  const fs::path dir = fs::temp_directory_path() / ("waam_program_limit_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path big = dir / "big.nc";
  { std::ofstream(big) << "G1 X0\n"; }
  fs::resize_file(big, planner::kMaxProgramBytes + 1);  // sparse: no disk used
  try {
    (void)ReadProgramFile(big, std::nullopt);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("more than the limit of"));
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace waam::analysis
