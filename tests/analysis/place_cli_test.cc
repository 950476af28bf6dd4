// End-to-end tests of `waam place`: a planted layout fault (the torch meets a clamp) gets a placement that passes,
// written as a scenario `waam check` passes; a part out of reach everywhere gets no layout, the nearest miss named;
// the same inputs give the same place.json (timings aside) on one and two threads, and with --exhaustive (no
// pruning) on four; with the coarse pass's branch and bound at work, the same place.json on one and two threads and
// the same answer as --exhaustive, each pruned score a bound on the whole one; a bad range is one line.
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace place_cli_test {
namespace fs = std::filesystem;
using cli_test::ReadJson;
using cli_test::RunWaam;
using cli_test::TempDir;

std::string Scenario(const char* name) { return std::string(WAAM_SOURCE_DIR) + "/scenarios/cell/" + name + ".yaml"; }

TEST(PlaceCliTest, ThePlantedClampFaultGetsAPlacementThatPasses) {
  const fs::path out = TempDir("place_clamp");
  std::string err;
  ASSERT_EQ(RunWaam("place " + Scenario("cell_torch_meets_clamp") + " -q -o " + out.string(), &err), 0) << err;
  const nlohmann::json place = ReadJson(out / "place.json");
  EXPECT_TRUE(place.at("feasible").get<bool>());
  EXPECT_EQ(place.at("best").at("violating_samples").get<int>(), 0);
  EXPECT_EQ(place.at("best").at("pass").get<std::string>(), "full");
  EXPECT_EQ(place.at("layouts").get<int>(), 8);
  EXPECT_EQ(place.at("tried").size(), 8u);
  // The scenario as written (the original's layout is a fault) is one waam check passes.
  EXPECT_TRUE(fs::exists(out / "place_margin.png"));
  const fs::path check = out / "check";
  ASSERT_EQ(RunWaam("check " + (out / "scenario.yaml").string() + " -q --no-images --no-program -o " + check.string(),
                    &err), 0) << err;
  EXPECT_TRUE(ReadJson(check / "check.json").at("ok").get<bool>());
  // The layout the search kept is not the planted one (yaw 0, centred), which fails.
  const nlohmann::json& best = place.at("best").at("layout");
  EXPECT_FALSE(best.at("part_yaw_deg").get<double>() == 0.0 && best.at("part_x_mm").get<double>() == 0.0 &&
               best.at("part_y_mm").get<double>() == 0.0);

  // Deterministic: the same answer and the same scores on one thread.
  const fs::path one = TempDir("place_clamp_1");
  ASSERT_EQ(RunWaam("place " + Scenario("cell_torch_meets_clamp") + " -q --no-images --threads 1 -o " + one.string(),
                    &err), 0) << err;
  nlohmann::json a = place, b = ReadJson(one / "place.json");
  a.erase("timing");
  b.erase("timing");
  EXPECT_EQ(a, b);

  // Without pruning (every resolved motion checked whole), on four threads: the same layout and the same scores.
  const fs::path whole = TempDir("place_clamp_exhaustive");
  ASSERT_EQ(RunWaam("place " + Scenario("cell_torch_meets_clamp") + " -q --no-images --exhaustive --threads 4 -o " +
                        whole.string(), &err), 0) << err;
  nlohmann::json c = ReadJson(whole / "place.json");
  EXPECT_FALSE(c.at("pruning").at("enabled").get<bool>());
  EXPECT_EQ(c.at("pruning").at("resolved_checks_abandoned").get<int>(), 0);
  c.erase("timing");
  c.erase("pruning");
  a.erase("pruning");
  EXPECT_EQ(a, c);
}

TEST(PlaceCliTest, TheCoarsePassPrunesWithTheSameAnswerOnAnyThreadCount) {
  // One finalist: the coarse pass runs in batches of 4, so the last two batches meet a bar.
  const std::string args = " -q --no-images --set place.finalists=1 --set place.coarse_layers=6"
                           " --set place.part_x_mm=[-20,20,20] --set place.part_y_mm=-20"
                           " --set place.part_yaw_deg=[45,315,90] -o ";
  const fs::path one = TempDir("place_prune_1"), two = TempDir("place_prune_2"), whole = TempDir("place_prune_x");
  std::string err;
  ASSERT_EQ(RunWaam("place " + Scenario("cell_torch_meets_clamp") + " --threads 1" + args + one.string(), &err), 0)
      << err;
  ASSERT_EQ(RunWaam("place " + Scenario("cell_torch_meets_clamp") + " --threads 2" + args + two.string(), &err), 0)
      << err;
  ASSERT_EQ(RunWaam("place " + Scenario("cell_torch_meets_clamp") + " --threads 2 --exhaustive" + args +
                        whole.string(), &err), 0)
      << err;
  nlohmann::json a = ReadJson(one / "place.json"), b = ReadJson(two / "place.json"), c = ReadJson(whole / "place.json");
  a.erase("timing");
  b.erase("timing");
  c.erase("timing");
  EXPECT_EQ(a.dump(2), b.dump(2)) << "place.json (timing aside) differs between one and two threads";
  ASSERT_GT(a.at("pruning").at("coarse_bounded").get<int>(), 0) << "the case no longer prunes: it tests nothing";
  EXPECT_EQ(c.at("pruning").at("coarse_bounded").get<int>(), 0);
  EXPECT_EQ(a.at("best"), c.at("best")) << "pruning changed the answer";
  EXPECT_EQ(a.at("full_checks"), c.at("full_checks"));
  ASSERT_EQ(a.at("tried").size(), c.at("tried").size());
  for (std::size_t i = 0; i < a.at("tried").size(); ++i) {
    const nlohmann::json& pruned = a.at("tried")[i];
    const nlohmann::json& exact = c.at("tried")[i];
    if (!pruned.at("coarse").contains("bounded")) {
      EXPECT_EQ(pruned, exact) << "layout " << i << " was checked whole: its score is the exhaustive one";
      continue;
    }
    // A bounded score: its margin and minima at least, its violating samples at most, the whole check's.
    const nlohmann::json& p = pruned.at("coarse");
    const nlohmann::json& x = exact.at("coarse");
    EXPECT_GE(p.at("margin").get<double>(), x.at("margin").get<double>()) << "layout " << i;
    EXPECT_GE(p.at("min_clearance_mm").get<double>(), x.at("min_clearance_mm").get<double>()) << "layout " << i;
    EXPECT_GE(p.at("min_j5_deg").get<double>(), x.at("min_j5_deg").get<double>()) << "layout " << i;
    EXPECT_GE(p.at("min_joint_margin_deg").get<double>(), x.at("min_joint_margin_deg").get<double>()) << "layout " << i;
    EXPECT_LE(p.at("violating_samples").get<int>(), x.at("violating_samples").get<int>()) << "layout " << i;
    EXPECT_FALSE(pruned.contains("full")) << "a pruned layout got the whole path";
  }
}

TEST(PlaceCliTest, APartOutOfReachEverywhereHasNoLayoutAndNamesTheNearestMiss) {
  const fs::path out = TempDir("place_out_of_reach");
  std::string err;
  EXPECT_EQ(RunWaam("place " + Scenario("cell_out_of_reach") + " -q --no-images --set place.part_x_mm=[-100,100,100]" +
                        " --set place.part_y_mm=0 --set place.part_yaw_deg=0 -o " + out.string(),
                    &err),
            3)
      << err;
  const nlohmann::json place = ReadJson(out / "place.json");
  EXPECT_FALSE(place.at("feasible").get<bool>());
  EXPECT_EQ(place.at("layouts").get<int>(), 3);
  EXPECT_GT(place.at("best").at("violating_samples").get<int>(), 0);
  EXPECT_THAT(place.at("best").at("worst_violation").at("what").get<std::string>(), ::testing::HasSubstr("unreachable"));
  EXPECT_GT(place.at("best").at("worst_violation").at("reach_excess_mm").get<double>(), 0.0);
}

TEST(PlaceCliTest, ARangeWithMinAboveMaxIsOneLine) {
  const fs::path out = TempDir("place_bad");
  std::string err;
  EXPECT_EQ(RunWaam("place " + Scenario("cell_ok") + " -q --set place.part_x_mm=[50,-50,10] -o " + out.string(), &err),
            2);
  EXPECT_THAT(err, ::testing::HasSubstr("place.part_x_mm"));
  EXPECT_THAT(err, ::testing::HasSubstr("min must not exceed max"));
  EXPECT_FALSE(fs::exists(out / "place.json"));
}

}  // namespace place_cli_test
}  // namespace waam::analysis
