// End-to-end tests of `waam plan`: outputs, their contract fields, determinism and exit codes of the executable.
#include "analysis/plan_command.h"

#include <hdf5.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "models/core/files.h"
#include "models/core/parallel.h"
#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using cli_test::TempDir;
using cli_test::ReadJson;
using cli_test::RunWaam;

fs::path WritePlateScenario(const fs::path& dir, const std::string& pattern, const std::string& extra_part = "") {
  const fs::path file = dir / "scenario.yaml";
  std::ofstream(file) << "name: plate\n"
                         "part:\n  generator: {type: plate_with_holes" << extra_part << "}\n"
                         "slicing:\n  type: planar\n  layer_height_mm: 2.0\n"
                         "path:\n  pattern: " << pattern << "\n  bead_width_mm: 6\n"
                         "process:\n  travel_speed_mm_min: 400\n  wire_feed_mm_min: 3200\n";
  return file;
}

TEST(PlanCommandTest, TimelineWaitsOutTheMinimumLayerTime) {
  const fs::path dir = TempDir("min_layer_time");
  PlanOptions options;
  options.scenario = WritePlateScenario(dir, "contour");
  options.out_dir = dir / "out";
  options.quiet = true;
  options.layer_images = false;
  options.overrides = {"process.interpass.min_layer_time_s=900", "path.island_order=round_robin"};
  RunPlan(options);
  const nlohmann::json timeline = ReadJson(options.out_dir / "plan.json")["timeline"];
  ASSERT_GE(timeline["layers"].size(), 2u);
  EXPECT_GT(timeline["wait_s"].get<double>(), 0.0);
  for (std::size_t l = 1; l < timeline["layers"].size(); ++l) {
    EXPECT_NEAR(timeline["layers"][l]["start_s"].get<double>() - timeline["layers"][l - 1]["start_s"].get<double>(),
                900.0, 1e-6)
        << "each layer lasts min_layer_time_s from its first arc start to the next one's (layer " << l << ")";
  }
}

TEST(PlanCommandTest, WritesTheContractFieldsAndFiles) {
  const fs::path dir = TempDir("contract");
  PlanOptions options;
  options.scenario = WritePlateScenario(dir, "continuous");
  options.out_dir = dir / "out";
  options.quiet = true;
  const planner::PlanResult result = RunPlan(options);

  const nlohmann::json plan = ReadJson(options.out_dir / "plan.json");
  for (const char* field : {"layers", "passes", "passes_per_layer", "path_elements", "weld_length_mm",
                            "travel_length_mm", "estimated_time_s", "retract", "mesh"}) {
    EXPECT_TRUE(plan.contains(field)) << "plan.json must have '" << field << "'";
  }
  EXPECT_EQ(plan["layers"].get<std::size_t>(), result.plan.layers.size());
  EXPECT_EQ(plan["passes_per_layer"].size(), result.plan.layers.size());
  EXPECT_GT(plan["weld_length_mm"].get<double>(), 0.0);
  EXPECT_EQ(plan["retract"]["travels"].get<std::size_t>(), result.plan.layers.empty() ? 0u : result.stats.passes)
      << "one approach per pass: the first from outside, the others from the previous pass's lift";
  EXPECT_TRUE(plan["mesh"]["watertight"].get<bool>());
  EXPECT_DOUBLE_EQ(plan["contour_tolerance_mm"].get<double>(), 0.01 * plan["bead_width_mm"].get<double>())
      << "slices simplified to w/100 before the pattern";
  const double uncovered_pct = plan["uncovered"]["pct"].get<double>();
  EXPECT_GE(uncovered_pct, 0.0);
  EXPECT_LT(uncovered_pct, 5.0) << "the scenario's pattern fits its part";
  EXPECT_GE(plan["uncovered"]["worst_layer_pct"].get<double>(), uncovered_pct);
  EXPECT_TRUE(plan["layer_details"][0].contains("uncovered_pct"));
  for (std::size_t i = 0; i < result.plan.layers.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "layer_%04zu.png", i);
    EXPECT_TRUE(fs::exists(options.out_dir / "layers" / name)) << name;
  }
  // The timeline (docs/TIMELINE.md): its total is the estimated time, its parts add up, one entry per layer.
  ASSERT_TRUE(plan.contains("timeline"));
  const nlohmann::json& timeline = plan["timeline"];
  const double total = timeline["total_s"].get<double>();
  EXPECT_DOUBLE_EQ(plan["estimated_time_s"].get<double>(), total);
  EXPECT_NEAR(total,
              timeline["arc_on_s"].get<double>() + timeline["travel_s"].get<double>() +
                  timeline["wait_s"].get<double>(),
              1e-6 * total);
  EXPECT_GT(timeline["travel_s"].get<double>(), 0.0) << "the approach and the moves between passes";
  ASSERT_EQ(timeline["layers"].size(), result.plan.layers.size());
  double last_end = 0.0;
  for (const nlohmann::json& layer : timeline["layers"]) {
    for (const char* field : {"layer", "start_s", "end_s", "arc_on_s", "travel_s", "wait_s"}) {
      EXPECT_TRUE(layer.contains(field)) << "timeline.layers[] must have '" << field << "'";
    }
    EXPECT_GE(layer["start_s"].get<double>(), last_end) << "layers follow each other";
    EXPECT_GT(layer["end_s"].get<double>(), layer["start_s"].get<double>());
    last_end = layer["end_s"].get<double>();
  }
  EXPECT_DOUBLE_EQ(result.stats.estimated_time_s, total);

  // plan.h5 holds every point of every layer.
  const hid_t file = H5Fopen((options.out_dir / "plan.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0) << "plan.h5 must open";
  const hid_t dataset = H5Dopen2(file, "/layers/layer_0000", H5P_DEFAULT);
  ASSERT_GE(dataset, 0);
  const hid_t space = H5Dget_space(dataset);
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(space, dims, nullptr);
  EXPECT_EQ(dims[0], result.plan.layers[0].points.size());
  EXPECT_EQ(dims[1], 11u);
  H5Sclose(space);
  H5Dclose(dataset);
  H5Fclose(file);

  // No temporary files are left behind.
  for (const auto& entry : fs::recursive_directory_iterator(options.out_dir)) {
    EXPECT_THAT(entry.path().string(), ::testing::Not(HasSubstr(".tmp-")));
  }
}

TEST(PlanCommandTest, IdenticalInputsGiveIdenticalPlans) {
  const fs::path dir = TempDir("determinism");
  PlanOptions options;
  options.scenario = WritePlateScenario(dir, "continuous");
  options.quiet = true;
  options.layer_images = false;
  options.out_dir = dir / "a";
  RunPlan(options);
  options.out_dir = dir / "b";
  RunPlan(options);
  EXPECT_EQ(ReadFile(dir / "a" / "plan.json"), ReadFile(dir / "b" / "plan.json"));
}

TEST(PlanCommandTest, SamePlanOnOneAndFourThreads) {
  const fs::path dir = TempDir("threads");
  PlanOptions options;
  options.quiet = true;
  options.layer_images = false;
  std::vector<fs::path> scenarios;
  for (const char* pattern : {"contour", "hybrid", "continuous"}) {
    fs::create_directories(dir / pattern);
    scenarios.push_back(WritePlateScenario(dir / pattern, pattern));
  }
  scenarios.push_back(fs::path(WAAM_SOURCE_DIR) / "scenarios" / "ribweb" / "cross_junction.yaml");
  // The other planners plan their layers in parallel too: cylinder, cone, multi-directional, skeleton.
  for (const char* name : {"multiaxis/fins_cylinder.yaml", "multiaxis/vanes_wide_cone.yaml",
                           "multiaxis/cup_two_handles.yaml", "distortion/small_bent_tube.yaml"}) {
    scenarios.push_back(fs::path(WAAM_SOURCE_DIR) / "scenarios" / name);
  }
  for (const fs::path& scenario : scenarios) {
    options.scenario = scenario;
    SetThreadCount(1);
    options.out_dir = dir / "one";
    RunPlan(options);
    SetThreadCount(4);
    options.out_dir = dir / "four";
    RunPlan(options);
    SetThreadCount(0);
    EXPECT_EQ(ReadFile(dir / "one" / "plan.json"), ReadFile(dir / "four" / "plan.json")) << scenario;
  }
  // The skeleton planner's per-layer path (the tube above plans one spiral).
  options.scenario = fs::path(WAAM_SOURCE_DIR) / "scenarios" / "distortion" / "small_bent_tube.yaml";
  options.overrides = {"path.pattern=contour"};
  SetThreadCount(1);
  options.out_dir = dir / "one";
  RunPlan(options);
  SetThreadCount(4);
  options.out_dir = dir / "four";
  RunPlan(options);
  SetThreadCount(0);
  EXPECT_EQ(ReadFile(dir / "one" / "plan.json"), ReadFile(dir / "four" / "plan.json")) << "skeleton, contour";
}

TEST(PlanCommandTest, ContinuousNeedsFewerPassesThanHybrid) {
  const fs::path dir = TempDir("hybrid");
  PlanOptions options;
  options.quiet = true;
  options.layer_images = false;
  options.scenario = WritePlateScenario(dir, "hybrid");
  options.out_dir = dir / "hybrid";
  const auto hybrid = RunPlan(options);
  options.scenario = WritePlateScenario(dir, "continuous");
  options.out_dir = dir / "continuous";
  const auto continuous = RunPlan(options);
  EXPECT_EQ(continuous.stats.passes, continuous.stats.layers) << "continuous: one pass per layer";
  EXPECT_GT(hybrid.stats.passes, continuous.stats.passes);
}

TEST(PlanCliTest, BadScenarioExitsTwoWithOneLineAndNoOutput) {
  const fs::path dir = TempDir("cli_bad");
  std::ofstream(dir / "bad.yaml") << "name: x\npart:\n  generator: {type: box}\nslicing:\n  layer_height_mm: -1\n";
  std::string err;
  const int code = RunWaam("plan " + (dir / "bad.yaml").string() + " -o " + (dir / "out").string(), &err);
  EXPECT_EQ(code, 2);
  EXPECT_THAT(err, HasSubstr("slicing.layer_height_mm = -1: must be in"));
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << "one line on stderr, got: " << err;
  EXPECT_FALSE(fs::exists(dir / "out" / "plan.json"));
}

// A zigzag on a torus's ring-shaped slices leaves 12 % of the sliced area without a bead (up to 18 % of a layer): the
// plan is written (exit 0) and one warning line names the pattern; the contour pattern covers it and says nothing.
TEST(PlanCliTest, WarnsWhenThePatternLeavesMuchOfALayerUncovered) {
  const fs::path dir = TempDir("uncovered");
  auto scenario = [&](const std::string& pattern) {
    const fs::path file = dir / (pattern + ".yaml");
    std::ofstream(file) << "name: torus\n"
                           "part:\n  generator: {type: torus, major_radius_mm: 60, minor_radius_mm: 9}\n"
                           "slicing:\n  type: planar\n  layer_height_mm: 3.0\n"
                           "path:\n  pattern: " << pattern << "\n  bead_width_mm: 6\n"
                           "process:\n  travel_speed_mm_min: 600\n  wire_feed_mm_min: 6000\n";
    return file.string();
  };
  std::string err;
  EXPECT_EQ(RunWaam("plan " + scenario("zigzag") + " -q --no-images -o " + (dir / "zigzag").string(), &err), 0);
  EXPECT_THAT(err, HasSubstr("warning: path.pattern 'zigzag' leaves"));
  EXPECT_THAT(err, HasSubstr("without a bead"));
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  const nlohmann::json plan = ReadJson(dir / "zigzag" / "plan.json");
  EXPECT_GT(plan["uncovered"]["pct"].get<double>(), 5.0);
  EXPECT_EQ(RunWaam("plan " + scenario("contour") + " -q --no-images -o " + (dir / "contour").string(), &err), 0);
  EXPECT_EQ(err, "") << "contours cover the rings";
}

// The progress bar of a skeleton plan (a bent tube: more layers along its axis than its height suggests) never counts
// past its total, and ends at the plan's layer count.
TEST(PlanCliTest, SkeletonProgressStaysWithinItsTotalAndEndsAtTheLayerCount) {
  const fs::path dir = TempDir("cli_skeleton_progress");
  std::string err;
  ASSERT_EQ(RunWaam("plan " + std::string(WAAM_SOURCE_DIR) + "/scenarios/distortion/small_bent_tube.yaml --no-images -o " +
                        (dir / "out").string(),
                    &err),
            0)
      << err;
  const nlohmann::json plan = ReadJson(dir / "out" / "plan.json");
  const std::size_t layers = plan.at("layers").get<std::size_t>();
  std::size_t draws = 0, last_done = 0, last_total = 0;
  for (std::size_t at = err.find("plan "); at != std::string::npos; at = err.find("plan ", at + 1)) {
    std::size_t done = 0, total = 0;
    const std::size_t bar = err.find("] ", at);
    if (bar == std::string::npos || std::sscanf(err.c_str() + bar + 2, "%zu/%zu layers", &done, &total) != 2) continue;
    EXPECT_LE(done, total) << err;
    ++draws, last_done = done, last_total = total;
  }
  ASSERT_GT(draws, 0u) << err;
  EXPECT_EQ(last_done, layers) << err;
  EXPECT_EQ(last_total, layers) << err;
}

TEST(PlanCliTest, MissingScenarioFileExitsTwo) {
  std::string err;
  EXPECT_EQ(RunWaam("plan /nonexistent/scenario.yaml -o /tmp/waam_never", &err), 2);
  EXPECT_THAT(err, HasSubstr("/nonexistent/scenario.yaml: file not found"));
}

TEST(PlanCliTest, HelpExplainsTheOutputs) {
  std::string err;
  const fs::path out = TempDir("help") / "help.txt";
  const int status = std::system((std::string(WAAM_BINARY) + " plan --help > " + out.string()).c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_THAT(ReadFile(out), HasSubstr("plan.json"));
}

}  // namespace
}  // namespace waam::analysis
