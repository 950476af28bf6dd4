// `waam tune-voids` on the four-arm cross junction (003 Fig. 30): the search lowers the void, its outputs, bad input.
#include "analysis/tune_voids_command.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analysis/plan_command.h"
#include "analysis/scenario.h"
#include "models/core/error.h"
#include "models/core/parallel.h"
#include "planner/plan_scenario.h"
#include "planner/scenario/scenario.h"

namespace waam::analysis {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kCross = fs::path(WAAM_SOURCE_DIR) / "scenarios/ribweb/cross_junction.yaml";

std::string FirstDataHeader(const fs::path& csv) {
  std::ifstream in(csv);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != '#') return line;
  }
  return "";
}

TEST(TuneVoids, CrossJunctionVoidFallsAsTheShiftGrows) {
  TuneVoidsOptions options;
  options.scenario = kCross;
  options.out_dir = fs::path(::waam_test_env::TempDir()) / "tune_cross";
  options.training_csv = options.out_dir / "junctions.csv";
  options.quiet = true;
  const TuneVoidsResult result = RunTuneVoids(options);
  ASSERT_EQ(result.junctions.size(), 1u) << "one junction class in the cross";
  const JunctionTuning& j = result.junctions[0];
  EXPECT_EQ(j.junction_class, "4 ribs 90/90/90/90");
  EXPECT_EQ(j.eta, 4);
  EXPECT_GT(j.plain.void_volume_mm3, options.threshold_mm3) << "plain contours leave a void at the cross";
  EXPECT_LT(j.geometric.void_volume_mm3, j.plain.void_volume_mm3) << "lambda = 1 fills part of it";
  EXPECT_TRUE(j.converged);
  EXPECT_LE(j.tuned.void_volume_mm3, options.threshold_mm3);
  EXPECT_GT(j.tuned.shift_mm, 0.0);
  // Monotonic: over every trial, a larger shift never leaves a larger void.
  std::vector<TuneTrial> trials = j.history;
  std::sort(trials.begin(), trials.end(), [](const auto& a, const auto& b) { return a.shift_mm < b.shift_mm; });
  for (std::size_t k = 1; k < trials.size(); ++k) {
    EXPECT_LE(trials[k].void_volume_mm3, trials[k - 1].void_volume_mm3)
        << "shift " << trials[k].shift_mm << " mm vs " << trials[k - 1].shift_mm << " mm";
  }
  // Outputs: tune.json with the tuned shift, both pictures, and an Appendix A1-format table.
  const nlohmann::json doc = nlohmann::json::parse(std::ifstream(options.out_dir / "tune.json"));
  EXPECT_DOUBLE_EQ(doc["junctions"][0]["shift_mm"].get<double>(), j.tuned.shift_mm);
  for (const std::string& picture : j.pictures) EXPECT_TRUE(fs::exists(options.out_dir / picture)) << picture;
  EXPECT_EQ(j.pictures.size(), 2u);
  EXPECT_EQ(FirstDataHeader(options.training_csv),
            FirstDataHeader(fs::path(WAAM_SOURCE_DIR) / "models/data/nguyen2022_appendixA1_junction_voids.csv"));

  // The planner takes the tuned shift back from tune.json (mode tuned).
  const std::string tune_file = (options.out_dir / "tune.json").string();
  const Scenario scenario =
      LoadScenario(kCross, {"path.void_filling.mode=tuned", "path.void_filling.tune_file=" + tune_file});
  const planner::PlanResult plan = planner::PlanScenario(scenario, nullptr);
  ASSERT_EQ(plan.void_corrections.size(), plan.plan.layers.size()) << "one corrected corner per layer";
  for (const planner::CornerCorrection& c : plan.void_corrections) EXPECT_NEAR(c.shift_mm, j.tuned.shift_mm, 1e-9);
  const nlohmann::json plan_json = PlanToJson(scenario, plan)["void_filling"];
  EXPECT_EQ(plan_json["corrected_corners"].get<std::size_t>(), plan.plan.layers.size());
  EXPECT_NEAR(plan_json["classes"]["4 ribs 90/90/90/90"]["mean_shift_mm"].get<double>(), j.tuned.shift_mm, 1e-9);
}

// The junction classes are tuned in parallel (and each class's plain and geometric trials): the same tune.json,
// byte for byte, on 1 and 4 threads, for a rib web with two classes.
TEST(TuneVoids, SameTuneJsonOnOneAndFourThreads) {
  std::string json[2];
  for (const int threads : {1, 4}) {
    TuneVoidsOptions options;
    options.scenario = fs::path(WAAM_SOURCE_DIR) / "scenarios/ribweb/rib_web_eulerian.yaml";
    options.out_dir = fs::path(::waam_test_env::TempDir()) / ("tune_threads_" + std::to_string(threads));
    options.quiet = true;
    options.images = false;
    SetThreadCount(threads);
    const TuneVoidsResult result = RunTuneVoids(options);
    SetThreadCount(0);
    ASSERT_EQ(result.junctions.size(), 2u) << "two junction classes tuned side by side";
    std::ifstream in(options.out_dir / "tune.json");
    json[threads == 1 ? 0 : 1].assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  EXPECT_FALSE(json[0].empty());
  EXPECT_EQ(json[0], json[1]);
}

TEST(TuneVoids, BadInputIsNamed) {
  TuneVoidsOptions options;
  options.scenario = kCross;
  options.out_dir = fs::path(::waam_test_env::TempDir()) / "tune_bad";
  options.quiet = true;
  options.layers = 1;
  try {
    RunTuneVoids(options);
    FAIL() << "expected InputError for one layer";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("tune-voids --layers = 1: must be in [2, 100]"));
  }
  options.layers = 3;
  options.overrides = {"part.generator.arm_angles_deg=[0, 180]"};
  try {
    RunTuneVoids(options);
    FAIL() << "expected InputError for a straight wall";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no junction of 3 or more ribs on the first layer"));
  }
}

}  // namespace
}  // namespace waam::analysis
