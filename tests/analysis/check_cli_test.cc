// End-to-end tests of `waam check` on the scenarios of scenarios/cell/: exit codes, the expected violation kind of
// each planted fault, and a bad cell model as a one-line error.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using cli_test::TempDir;
using cli_test::Slurp;

// Runs `waam check` on `scenario` into `out`, returning the exit code; stderr goes to *err.
int RunCheckCli(const fs::path& scenario, const fs::path& out, std::string* err) {
  const fs::path err_file = out.parent_path() / (out.filename().string() + ".stderr");
  const std::string command = std::string(WAAM_BINARY) + " check " + scenario.string() + " -o " + out.string() +
                              " -q --no-images >/dev/null 2>" + err_file.string();
  const int status = std::system(command.c_str());
  *err = Slurp(err_file);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::set<std::string> Kinds(const nlohmann::json& check) {
  std::set<std::string> kinds;
  for (const nlohmann::json& v : check.at("violations")) kinds.insert(v.at("kind").get<std::string>());
  return kinds;
}

struct Case {
  const char* scenario;
  int exit_code;
  std::set<std::string> kinds;
};

// Checks one scenario of scenarios/cell/ end to end: its exit code, its violation kinds, the programs written and the
// cell and robot it names.
void ExpectCase(const Case& c) {
  const fs::path out = TempDir(c.scenario);
  std::string err;
  const int code = RunCheckCli(fs::path(WAAM_SOURCE_DIR) / "scenarios" / "cell" / (std::string(c.scenario) + ".yaml"),
                               out, &err);
  EXPECT_EQ(code, c.exit_code) << c.scenario << ": " << err;
  ASSERT_TRUE(fs::exists(out / "check.json")) << c.scenario << ": " << err;
  const nlohmann::json check = nlohmann::json::parse(Slurp(out / "check.json"));
  EXPECT_EQ(check.at("ok").get<bool>(), c.exit_code == 0) << c.scenario;
  EXPECT_EQ(Kinds(check), c.kinds) << c.scenario << ": " << check.at("violations").dump(1);
  EXPECT_GT(check.at("points").get<int>(), 0) << c.scenario;
  EXPECT_TRUE(fs::exists(out / "program.csv")) << c.scenario;
  EXPECT_TRUE(fs::exists(out / "program.ls")) << c.scenario;
  const std::string name = c.scenario;
  const std::string type = name.find("_turntable") != std::string::npos ? "turntable"
                           : name.find("_table") != std::string::npos   ? "none"
                                                                         : "tilt_rotate";
  EXPECT_EQ(check.at("cell").at("positioner_type").get<std::string>(), type) << c.scenario;
  if (name.rfind("preset_", 0) == 0) {
    // A preset names its arm vendor first and itself as the source, with the closed-form IK.
    const std::string preset = name.substr(7, name.find("_out_of_reach") == std::string::npos
                                                  ? std::string::npos
                                                  : name.find("_out_of_reach") - 7);
    EXPECT_EQ(check.at("robot").at("source").get<std::string>(), preset) << c.scenario;
    EXPECT_EQ(check.at("robot").at("ik").get<std::string>(), "closed_form") << c.scenario;
    const std::string robot = check.at("robot").at("name").get<std::string>();
    EXPECT_TRUE(robot.rfind("FANUC ", 0) == 0 || robot.rfind("ABB ", 0) == 0 || robot.rfind("KUKA ", 0) == 0 ||
                robot.rfind("Yaskawa ", 0) == 0)
        << c.scenario << ": " << robot;
  }
}

// One scenario of each kind of cell (MJCF, URDF, preset arm; tilt-rotate, turntable and no positioner) and the reach
// and clamp-collision faults: the run the sanitizer build checks.
TEST(CheckCliTest, EachKindOfCellGivesItsExpectedResult) {
  const Case cases[] = {
      {"cell_ok", 0, {}},
      {"cell_out_of_reach", 3, {"unreachable"}},
      {"cell_torch_meets_clamp", 3, {"collision"}},
      {"urdf_kr16_out_of_reach", 3, {"unreachable"}},
      {"preset_abb_irb1600_out_of_reach", 3, {"unreachable"}},
      {"preset_kuka_kr16_turntable", 0, {}},
      {"preset_abb_irb1600_table", 0, {}},
  };
  for (const Case& c : cases) ExpectCase(c);
}

// The other scenarios of scenarios/cell/: the other presets and planted faults (Release only, tools/sanitize.sh; the
// joint-limit and plate-collision faults' checks are sanitized by PlantedFaultTest and SetOverridesTheCellPlacement).
TEST(CheckCliTest, EveryOtherCellScenarioGivesItsExpectedResult) {
  const Case cases[] = {
      {"cell_joint_limit", 3, {"joint_limit"}},
      {"urdf_kr16", 0, {}},
      {"preset_fanuc_arcmate100ic", 0, {}},
      {"preset_abb_irb1600", 0, {}},
      {"preset_kuka_kr16", 0, {}},
      {"preset_yaskawa_mh12", 0, {}},
      {"cell_torch_into_plate", 3, {"collision"}},
  };
  for (const Case& c : cases) ExpectCase(c);
}

TEST(CheckCliTest, SetOverridesTheCellPlacement) {
  // The well placed cell turned away from the positioner with --set: the j1 fault of cell_joint_limit.yaml.
  const fs::path out = TempDir("set");
  const std::string command = std::string(WAAM_BINARY) + " check " + WAAM_SOURCE_DIR +
                              "/scenarios/cell/cell_ok.yaml --set cell.robot.yaw_deg=180 -q --no-images -o " +
                              out.string() + " >/dev/null 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3);
  const nlohmann::json check = nlohmann::json::parse(Slurp(out / "check.json"));
  EXPECT_EQ(Kinds(check), std::set<std::string>{"joint_limit"});
}

TEST(CheckCliTest, BrokenCellModelIsABadInputError) {
  const fs::path dir = TempDir("bad_model");
  std::ofstream(dir / "broken.xml") << "<mujoco><worldbody><body></mujoco>\n";
  std::string scenario = Slurp(fs::path(WAAM_SOURCE_DIR) / "scenarios" / "cell" / "cell_ok.yaml");
  scenario.replace(scenario.find("cell:\n"), 6, "cell:\n  mjcf: broken.xml\n");
  std::ofstream(dir / "s.yaml") << scenario;
  std::string err;
  EXPECT_EQ(RunCheckCli(dir / "s.yaml", dir / "out", &err), 2);
  EXPECT_THAT(err, HasSubstr("waam: error: "));
  EXPECT_THAT(err, HasSubstr("broken.xml"));
  EXPECT_FALSE(fs::exists(dir / "out" / "check.json"));
}

// `waam check` with cell.checks.mode continuous on the KR 16-2 class arm of tests/data/urdf_fallback/`urdf`; returns
// check.json (exit code 0 or 3) and the exit code in *code.
nlohmann::json CheckContinuousUrdf(const std::string& urdf, int* code) {
  const fs::path dir = TempDir("urdf_" + urdf);
  std::string scenario = Slurp(fs::path(WAAM_SOURCE_DIR) / "scenarios" / "cell" / "urdf_kr16.yaml");
  const std::string from = "robots/waam_kr16_support/urdf/kr16_2.urdf";
  scenario.replace(scenario.find(from), from.size(),
                   (fs::path(WAAM_SOURCE_DIR) / "tests" / "data" / "urdf_fallback" / urdf).string());
  const std::string checks = "part_collision: true}";
  scenario.replace(scenario.find(checks), checks.size(), "part_collision: true, mode: continuous}");
  std::ofstream(dir / "s.yaml") << scenario;
  std::string err;
  *code = RunCheckCli(dir / "s.yaml", dir / "out", &err);
  EXPECT_TRUE(*code == 0 || *code == 3) << err;
  return nlohmann::json::parse(Slurp(dir / "out" / "check.json"));
}

// A URDF link drawn but without collision geometry, or a collision mesh that is not closed: the continuous check
// runs discrete and check.json names the link (one line) in mode_fallback, never silently.
TEST(CheckCliTest, UrdfLinkWithoutCollisionFallsBackToDiscrete) {
  int code = 0;
  const nlohmann::json check = CheckContinuousUrdf("link_without_collision.urdf", &code);
  EXPECT_EQ(check.at("mode"), "discrete");
  const std::string why = check.at("mode_fallback").get<std::string>();
  EXPECT_THAT(why, HasSubstr("link_without_collision.urdf:"));
  EXPECT_THAT(why, HasSubstr("link 'link_5' has <visual> but no <collision> geometry"));
  EXPECT_EQ(why.find('\n'), std::string::npos);
}

TEST(CheckCliTest, UrdfOpenMeshFallsBackToDiscrete) {
  int code = 0;
  const nlohmann::json check = CheckContinuousUrdf("open_mesh.urdf", &code);
  EXPECT_EQ(check.at("mode"), "discrete");
  const std::string why = check.at("mode_fallback").get<std::string>();
  EXPECT_THAT(why, HasSubstr("geom link_5_collision0 (body link_5): its mesh is not closed (4 edges"));
  EXPECT_EQ(why.find('\n'), std::string::npos);
}

// A continuous joint with a velocity limit: its travel between samples bounds its motion as any axis's does, so the
// continuous check runs (its range is one turn each way, +-360 deg, for the joint limit check).
TEST(CheckCliTest, UrdfContinuousJointWithVelocityRunsContinuous) {
  int code = 0;
  const nlohmann::json check = CheckContinuousUrdf("continuous_joint.urdf", &code);
  EXPECT_EQ(code, 0);
  EXPECT_EQ(check.at("mode"), "continuous");
  EXPECT_EQ(check.at("mode_fallback"), "");
}

}  // namespace
}  // namespace waam::analysis
