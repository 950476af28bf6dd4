// `waam run` and `waam bench` on a tiny scenario: step outputs, summary.json, determinism apart from `timing`,
// step selection errors, the bench's child processes, resume and report.
#include "analysis/run_command.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/bench_command.h"
#include "models/core/data_dir.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using cli_test::ReadJson;

constexpr const char* kTinyScenario = cli_test::kTinyBlockScenario;

fs::path WriteScenario(const std::string& name, const std::string& text) {
  // Per process: tests writing the same scenario run in parallel under ctest -j.
  const fs::path dir = fs::path(::waam_test_env::TempDir()) / ("waam_test_run_scenarios_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / (name + ".yaml");
  std::ofstream(file) << text;
  return file;
}

RunOptions TinyRun(const std::string& out_name) {
  RunOptions options;
  options.scenario = WriteScenario("tiny_block", kTinyScenario);
  options.out_dir = fs::path(::waam_test_env::TempDir()) / out_name;
  options.quiet = true;
  options.images = false;
  fs::remove_all(options.out_dir);
  return options;
}

TEST(RunCommand, RunsTheDefaultChainIntoOneFolderPerStep) {
  const RunOptions options = TinyRun("waam_test_run_default_chain");
  const RunSummary summary = RunScenario(options);
  ASSERT_EQ(summary.steps.size(), 3u) << "default chain: plan, check, simulate";
  EXPECT_EQ(summary.steps[0].name, "plan");
  EXPECT_EQ(summary.steps[1].name, "check");
  EXPECT_EQ(summary.steps[2].name, "simulate");
  for (const char* file : {"plan/plan.json", "check/check.json", "simulate/simulate.json", "summary.json"}) {
    EXPECT_TRUE(fs::exists(options.out_dir / file)) << "expected output " << file;
  }
  const nlohmann::json j = ReadJson(options.out_dir / "summary.json");
  EXPECT_EQ(j["scenario"], "tiny_block");
  EXPECT_EQ(j["exit_code"].get<int>(), summary.exit_code);
  EXPECT_EQ(j["as_expected"].get<bool>(), summary.exit_code == 0);
  ASSERT_EQ(j["steps"].size(), 3u);
  // The summary's metrics are the step outputs' own numbers.
  const nlohmann::json plan = ReadJson(options.out_dir / "plan/plan.json");
  EXPECT_EQ(j["steps"][0]["metrics"]["layers"], plan["layers"]);
  EXPECT_EQ(j["steps"][0]["metrics"]["weld_length_mm"], plan["weld_length_mm"]);
  const nlohmann::json sim = ReadJson(options.out_dir / "simulate/simulate.json");
  EXPECT_EQ(j["steps"][2]["metrics"]["deposited_volume_mm3"], sim["deposited_volume_mm3"]);
  EXPECT_EQ(j["steps"][2]["metrics"]["deviation/rms_mm"], sim["deviation"]["rms_mm"]);
  const nlohmann::json check = ReadJson(options.out_dir / "check/check.json");
  EXPECT_EQ(j["steps"][1]["exit_code"].get<int>(), check["ok"].get<bool>() ? 0 : 3);
  // Timings only under `timing`.
  ASSERT_TRUE(j.contains("timing"));
  for (const char* step : {"plan", "check", "simulate"}) {
    EXPECT_GE(j["timing"]["steps"][step]["wall_s"].get<double>(), 0.0) << step;
    EXPECT_GT(j["timing"]["steps"][step]["peak_rss_mb"].get<double>(), 0.0) << step;
  }
}

TEST(RunCommand, TwoRunsGiveIdenticalJsonApartFromTimings) {
  RunOptions first = TinyRun("waam_test_run_determinism_1");
  RunOptions second = TinyRun("waam_test_run_determinism_2");
  RunScenario(first);
  RunScenario(second);
  nlohmann::json a = ReadJson(first.out_dir / "summary.json"), b = ReadJson(second.out_dir / "summary.json");
  a.erase("timing");
  b.erase("timing");
  EXPECT_EQ(a.dump(2), b.dump(2)) << "summary.json differs between two runs outside `timing`";
  EXPECT_EQ(ReadFile(first.out_dir / "plan/plan.json"), ReadFile(second.out_dir / "plan/plan.json"));
  EXPECT_EQ(ReadFile(first.out_dir / "check/check.json"), ReadFile(second.out_dir / "check/check.json"));
  nlohmann::json sa = ReadJson(first.out_dir / "simulate/simulate.json");
  nlohmann::json sb = ReadJson(second.out_dir / "simulate/simulate.json");
  sa.erase("performance");  // simulate.json keeps its own timings under `performance`
  sb.erase("performance");
  EXPECT_EQ(sa.dump(2), sb.dump(2)) << "simulate.json differs between two runs outside `performance`";
}

TEST(RunCommand, ScenarioStepsAndImplicitPlan) {
  RunOptions options = TinyRun("waam_test_run_scenario_steps");
  options.scenario =
      WriteScenario("tiny_simulate_only", std::string(kTinyScenario) + "run:\n  steps: [simulate]\n");
  const RunSummary summary = RunScenario(options);
  ASSERT_EQ(summary.steps.size(), 2u) << "simulate needs the plan, which runs first";
  EXPECT_EQ(summary.steps[0].name, "plan");
  EXPECT_EQ(summary.steps[1].name, "simulate");
  EXPECT_FALSE(fs::exists(options.out_dir / "check")) << "check was not asked for";
}

// The optional steps run only when listed; tune_voids writes tune.json into its folder and reports each junction class.
TEST(RunCommand, TuneVoidsRunsWhenListed) {
  RunOptions options = TinyRun("waam_test_run_tune_voids");
  options.scenario = fs::path(WAAM_SOURCE_DIR) / "scenarios" / "ribweb" / "three_rib_junction.yaml";
  options.steps = {"tune_voids"};
  const RunSummary summary = RunScenario(options);
  ASSERT_EQ(summary.steps.size(), 1u);
  EXPECT_EQ(summary.steps[0].name, "tune_voids");
  EXPECT_TRUE(fs::exists(options.out_dir / "tune_voids" / "tune.json"));
  const nlohmann::json run = ReadJson(options.out_dir / "summary.json");
  EXPECT_EQ(run["steps"][0]["metrics"]["junction_classes"], 1) << run.dump();
}

TEST(RunCommand, UnknownStepNamesTheScenarioKey) {
  RunOptions options = TinyRun("waam_test_run_unknown_step");
  options.scenario = WriteScenario("tiny_bad_step", std::string(kTinyScenario) + "run:\n  steps: [plan, weld]\n");
  try {
    RunScenario(options);
    FAIL() << "expected an InputError for the unknown step";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("run.steps"));
    EXPECT_THAT(e.what(), HasSubstr("unknown step 'weld'"));
    EXPECT_THAT(e.what(), HasSubstr("plan, check, simulate"));
  }
  options.scenario = WriteScenario("tiny_tiny", kTinyScenario);
  options.steps = {"simulate", "plan"};
  EXPECT_THROW(
      try { RunScenario(options); } catch (const InputError& e) {
        EXPECT_THAT(e.what(), HasSubstr("needs 'plan' before it"));
        throw;
      },
      InputError);
}

TEST(RunCommand, BadRunSectionIsRefused) {
  RunOptions options = TinyRun("waam_test_run_bad_section");
  options.scenario = WriteScenario("tiny_bad_exit", std::string(kTinyScenario) + "run:\n  expected_exit_code: 2\n");
  EXPECT_THROW(
      try { RunScenario(options); } catch (const InputError& e) {
        EXPECT_THAT(e.what(), HasSubstr("run.expected_exit_code"));
        throw;
      },
      InputError);
  options.scenario = WriteScenario("tiny_bad_list", std::string(kTinyScenario) + "run:\n  steps: plan\n");
  EXPECT_THROW(
      try { RunScenario(options); } catch (const InputError& e) {
        EXPECT_THAT(e.what(), HasSubstr("must be a list of strings"));
        throw;
      },
      InputError);
}

TEST(BenchCommand, RunsEachScenarioInAChildAndResumes) {
  const fs::path dir = fs::path(::waam_test_env::TempDir()) / "waam_test_bench_scenarios";
  fs::remove_all(dir);
  fs::create_directories(dir / "faults");
  std::ofstream(dir / "tiny.yaml") << kTinyScenario << "run:\n  steps: [plan, simulate]\n";
  // A scenario that cannot run: the bench reports it as a failure with its one-line error and goes on.
  std::ofstream(dir / "faults" / "broken.yaml") << "name: broken\n";
  BenchOptions options;
  options.scenarios = {dir};
  options.out_dir = fs::path(::waam_test_env::TempDir()) / "waam_test_bench_out";
  fs::remove_all(options.out_dir);
  options.waam_binary = WAAM_BINARY;
  options.quiet = true;
  const nlohmann::json bench = RunBench(options);
  ASSERT_EQ(bench["scenarios"].size(), 2u);
  const nlohmann::json& broken = bench["scenarios"][0];
  EXPECT_EQ(broken["id"], "faults-broken") << "ids are the path under the folder";
  EXPECT_EQ(broken["outcome"], "fail");
  EXPECT_THAT(broken["error"].get<std::string>(), HasSubstr("part"));
  const nlohmann::json& tiny = bench["scenarios"][1];
  EXPECT_EQ(tiny["outcome"], "pass");
  EXPECT_GT(tiny["timing"]["peak_rss_mb"].get<double>(), 0.0) << "peak memory of the child process";
  EXPECT_EQ(bench["counts"]["fail"].get<int>(), 1);
  EXPECT_TRUE(fs::exists(options.out_dir / "tiny" / "summary.json"));
  const std::string report = ReadFile(options.out_dir / "report.html");
  // (Checked with find, not HasSubstr: on failure gmock would print the whole multi-megabyte page.)
  EXPECT_NE(report.find("scenario tiny_block"), std::string::npos) << "the report names the scenario";
  EXPECT_NE(report.find("<td>2</td>"), std::string::npos) << "the overview lists the plan's 2 layers";
  EXPECT_NE(report.find("<svg"), std::string::npos) << "model plots are inline SVG";
  EXPECT_NE(report.find("data:image/png;base64,"), std::string::npos) << "pictures are embedded";
  EXPECT_EQ(report.find("<script"), std::string::npos) << "the report is self-contained";
  EXPECT_EQ(report.find("src=\"http"), std::string::npos) << "no external resources";
  EXPECT_EQ(report.find("<link"), std::string::npos) << "no external style sheets";

  // Resume: the completed result is reused, not rerun (its bench_entry.json is not rewritten).
  const auto stamp = fs::last_write_time(options.out_dir / "tiny" / "bench_entry.json");
  const nlohmann::json again = RunBench(options);
  EXPECT_EQ(again["timing"]["reused_results"].get<int>(), 2);
  EXPECT_EQ(fs::last_write_time(options.out_dir / "tiny" / "bench_entry.json"), stamp);
  nlohmann::json a = bench["scenarios"], b = again["scenarios"];
  EXPECT_EQ(a.dump(), b.dump());
}

// `waam bench` with no list outside the repository: the example scenarios of the data folder, or one line saying
// what to give it when there are none.
TEST(BenchCommand, NoListOutsideTheRepositoryRunsTheExamplesOrSaysWhatToGive) {
  const fs::path here = fs::current_path();
  const fs::path elsewhere = fs::temp_directory_path() / ("waam_bench_cwd_" + std::to_string(::getpid()));
  fs::create_directories(elsewhere);
  fs::current_path(elsewhere);
  const auto examples = BenchScenarios({});
  ::setenv("WAAM_DATA_DIR", elsewhere.c_str(), 1);
  std::string message;
  try {
    BenchScenarios({});
  } catch (const InputError& e) {
    message = e.what();
  }
  ::unsetenv("WAAM_DATA_DIR");
  fs::current_path(here);
  ASSERT_FALSE(examples.empty());
  EXPECT_EQ(examples.front().first.string().rfind((DataDir() / "scenarios").string(), 0), 0u)
      << "the installed example scenarios: " << examples.front().first;
  EXPECT_THAT(message, HasSubstr("give scenario files or folders"));
}

TEST(BenchCommand, MissingScenarioIsABadInputError) {
  try {
    BenchScenarios({"/nonexistent/scenario.yaml"});
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/scenario.yaml: scenario file not found"));
  }
}

}  // namespace
}  // namespace waam::analysis

namespace waam::analysis {
namespace {

TEST(BenchReference, ComparesPublishedFiguresWithOurResults) {
  auto entry = [](const std::string& name, const std::string& step, const std::string& key, double value) {
    return nlohmann::json{{"id", name}, {"scenario", name},
                          {"steps", {{{"name", step}, {"metrics", {{key, value}}}}}}};
  };
  const nlohmann::json scenarios = {entry("plate_continuous", "simulate", "ra_mm", 1.0),
                                    entry("plate_hybrid", "simulate", "ra_mm", 4.0),
                                    entry("block_existing", "simulate", "boundary_lag_mm", 2.5)};
  const nlohmann::json rows = ReferenceComparison(scenarios);
  std::map<std::string, nlohmann::json> by_id;
  for (const nlohmann::json& r : rows) by_id[r["id"]] = r;
  ASSERT_TRUE(by_id.count("ding_ra"));
  EXPECT_DOUBLE_EQ(by_id["ding_ra"]["ours"].get<double>(), 75.0) << "100 (1 - 1/4)";
  EXPECT_DOUBLE_EQ(by_id["nguyen_lag_existing"]["ours"].get<double>(), 2.5);
  EXPECT_DOUBLE_EQ(by_id["nguyen_lag_existing"]["published_value"].get<double>(), 2.7);
  EXPECT_TRUE(by_id["ding_a_passes"]["ours"].is_null()) << "ding_a was not benched";
  // Model rows come from models/data/*.json, whatever was benched.
  EXPECT_NEAR(by_id["nguyen_speed_height_b"]["ours"].get<double>(), -2.069, 0.05);
  EXPECT_NEAR(by_id["dai_csw_r2"]["ours"].get<double>(), 0.98, 0.01);
}

}  // namespace
}  // namespace waam::analysis

namespace waam::analysis {
namespace {

// Runs `waam <arguments>` and returns its exit code; stderr goes to *err.
int RunWaamCli(const std::string& arguments, std::string* err) {
  // Per process: the RunCli tests run in parallel under ctest -j, each in its own process.
  const fs::path err_file =
      fs::path(::waam_test_env::TempDir()) / ("waam_test_run_cli_" + std::to_string(::getpid()) + ".stderr");
  const std::string command = std::string(WAAM_BINARY) + " " + arguments + " >/dev/null 2>" + err_file.string();
  const int status = std::system(command.c_str());
  *err = ReadFile(err_file);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(RunCli, PlantedCellFaultExitsThreeAsExpected) {
  const fs::path out = fs::path(::waam_test_env::TempDir()) / "waam_test_run_cli_fault";
  fs::remove_all(out);
  std::string err;
  const fs::path scenario = fs::path(WAAM_SOURCE_DIR) / "scenarios" / "cell" / "cell_out_of_reach.yaml";
  EXPECT_EQ(RunWaamCli("run " + scenario.string() + " -o " + out.string() + " -q --no-images --steps plan check",
                       &err), 3) << err;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["expected_exit_code"].get<int>(), 3) << "the planted fault declares run.expected_exit_code";
  EXPECT_TRUE(summary["as_expected"].get<bool>());
  EXPECT_EQ(summary["steps"][1]["status"], "violations");
}

// A list option takes its items comma separated or space separated (and both at once).
TEST(RunCli, StepsCommaOrSpaceSeparated) {
  const fs::path scenario = WriteScenario("tiny_block", kTinyScenario);
  for (const std::string steps : {"plan,simulate", "plan simulate", "plan, simulate"}) {
    const fs::path out = fs::path(::waam_test_env::TempDir()) / "waam_test_run_cli_steps";
    fs::remove_all(out);
    std::string err;
    ASSERT_EQ(RunWaamCli("run " + scenario.string() + " -o " + out.string() + " -q --no-images --steps " + steps,
                         &err), 0) << "--steps " << steps << ": " << err;
    const nlohmann::json summary = ReadJson(out / "summary.json");
    ASSERT_EQ(summary["steps"].size(), 2u) << "--steps " << steps;
    EXPECT_EQ(summary["steps"][0]["name"], "plan");
    EXPECT_EQ(summary["steps"][1]["name"], "simulate");
  }
  std::string err;
  EXPECT_EQ(RunWaamCli("run " + scenario.string() + " -o " + ::waam_test_env::TempDir() + "/waam_test_run_cli_steps_bad" +
                       " -q --steps plan,weld", &err), 2);
  EXPECT_THAT(err, HasSubstr("weld"));
  EXPECT_THAT(err, ::testing::Not(HasSubstr("plan,weld"))) << "the list is split before the names are checked";
}

TEST(RunCli, BadScenarioIsExitTwoWithOneLine) {
  const fs::path scenario = WriteScenario("tiny_bad_layer", "name: x\npart:\n  generator: {type: box}\n"
                                                            "slicing:\n  layer_height_mm: -1\n");
  std::string err;
  EXPECT_EQ(RunWaamCli("run " + scenario.string() + " -o " + ::waam_test_env::TempDir() + "/waam_test_run_cli_bad", &err), 2);
  EXPECT_THAT(err, HasSubstr("waam: error:"));
  EXPECT_THAT(err, HasSubstr("slicing.layer_height_mm"));
}

}  // namespace
}  // namespace waam::analysis
