// The planner's sections of scenario files: loaded by analysis::LoadScenario (with the files they name), then planned.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/scenario.h"
#include "models/core/error.h"
#include "planner/path/junctions.h"
#include "planner/plan_scenario.h"

namespace waam::planner {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

class CentroidScenarioTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("waam_cup_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string ErrorOf(const std::string& slicing) {
    const fs::path file = dir_ / "cup.yaml";
    std::ofstream(file) << "name: cup\npart:\n  generator: {type: cup_two_handles}\nslicing:\n" << slicing
                        << "path: {pattern: contour, bead_width_mm: 5}\n"
                           "process: {travel_speed_mm_min: 600, wire_feed_mm_min: 2200, wire_diameter_mm: 1.2}\n";
    try {
      analysis::LoadScenario(file);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "expected an InputError for:\n" << slicing;
    return "";
  }

  fs::path dir_;
};

TEST_F(CentroidScenarioTest, BadSplitSettingsAreNamed) {
  const std::string head = "  type: multi_directional\n  layer_height_mm: 1.1\n";
  EXPECT_THAT(ErrorOf(head + "  split: centroid\n"), HasSubstr("slicing.split"));
  EXPECT_THAT(ErrorOf(head + "  split: centroid_shift\n  overhang_deg: 85\n"), HasSubstr("slicing.overhang_deg"));
  EXPECT_THAT(ErrorOf(head + "  split: centroid_shift\n  sub_volumes: [{name: a, direction: [0, 0, 1]}]\n"),
              HasSubstr("split = centroid_shift finds the sub-volumes itself"));
  EXPECT_THAT(ErrorOf(head + "  sub_volumes: [{name: a, direction: [0, 0, 1]}]\n  overhang_deg: 20\n"),
              HasSubstr("overhang_deg"));
}

// Every rib-web scenario plans; the Eulerian ones with one pass per layer.
TEST(Eulerian, RibWebScenariosPlan) {
  int eulerian = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(WAAM_SOURCE_DIR) + "/scenarios/ribweb")) {
    if (entry.path().extension() != ".yaml") continue;
    const analysis::Scenario scenario = analysis::LoadScenario(entry.path());
    const PlanResult result = PlanScenario(scenario, nullptr);
    ASSERT_FALSE(result.plan.layers.empty()) << entry.path();
    if (scenario.path.pattern != Pattern::kEulerian) continue;
    ++eulerian;
    for (std::size_t n : result.stats.passes_per_layer) EXPECT_EQ(n, 1u) << entry.path();
  }
  EXPECT_GE(eulerian, 4) << "rib web, cross, k-shaped and three-rib junction";
}

TEST(SkeletonPlanner, ScenarioKeysAreChecked) {
  const std::filesystem::path file = std::filesystem::path(WAAM_SOURCE_DIR) / "scenarios/tubes/part_1.yaml";
  EXPECT_THROW(
      {
        try {
          analysis::LoadScenario(std::filesystem::path(WAAM_SOURCE_DIR) / "scenarios/cylinder.yaml", {"path.pattern=spiral"});
        } catch (const InputError& e) {
          EXPECT_THAT(e.what(), HasSubstr("path.pattern = spiral: needs slicing.type = skeleton"));
          throw;
        }
      },
      InputError);
  EXPECT_THROW(
      {
        try {
          analysis::LoadScenario(file, {"slicing.h_max_mm=0.5"});
        } catch (const InputError& e) {
          EXPECT_THAT(e.what(), HasSubstr("slicing.h_max_mm = 0.5: must be >= slicing.h_min_mm = 1"));
          throw;
        }
      },
      InputError);
  EXPECT_THROW(
      {
        try {
          analysis::LoadScenario(file, {"path.pattern=zigzag"});
        } catch (const InputError& e) {
          EXPECT_THAT(e.what(), HasSubstr("use spiral (one pass) or contour"));
          throw;
        }
      },
      InputError);
}

TEST(VoidFilling, ScenarioSectionErrors) {
  const auto dir = std::filesystem::temp_directory_path() / ("waam_void_filling_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  auto error_of = [&](const std::string& section) -> std::string {
    std::ofstream(dir / "s.yaml") << "name: t\npart:\n  generator: {type: box}\nslicing:\n  layer_height_mm: 2\n"
                                     "path:\n  pattern: eulerian\n  bead_width_mm: 6\n"
                                  << section << "process:\n  travel_speed_mm_min: 400\n  wire_feed_mm_min: 3200\n";
    try {
      analysis::LoadScenario(dir / "s.yaml");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_THAT(error_of("  void_filling: {mode: tuned}\n"), HasSubstr("mode tuned needs tune_file"));
  EXPECT_THAT(error_of("  void_filling: {mode: fixed, lambda: -1}\n"), HasSubstr("path.void_filling.lambda = -1"));
  EXPECT_THAT(error_of("  void_filling: {mode: guess}\n"), HasSubstr("path.void_filling.mode = 'guess'"));
  EXPECT_THAT(error_of("  void_filling: {mode: fixed, lamda: 1}\n"), HasSubstr("path.void_filling.lamda: unknown key"));
  EXPECT_THAT(error_of("  void_filling: {mode: tuned, tune_file: none.json}\n"), HasSubstr("none.json not found"));
  EXPECT_EQ(error_of("  void_filling: {mode: fixed, lambda: 1.5}\n"), "");
  std::filesystem::remove_all(dir);
}

// The junction generator's parts (cross, k-shaped, three-rib) are found as one junction of the class they are built as.
TEST(Junctions, GeneratedJunctionsHaveTheirClass) {
  const std::map<std::string, std::string> expected = {{"0,90,180,270", "4 ribs 90/90/90/90"},
                                                       {"90,270,30,330", "4 ribs 180/60/60/60"},
                                                       {"90,210,330", "3 ribs 120/120/120"}};
  for (const auto& [arms, name] : expected) {
    const auto dir = std::filesystem::temp_directory_path() / ("waam_junction_gen_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "j.yaml") << "name: j\npart:\n  generator: {type: junction, arm_angles_deg: [" << arms
                                  << "], arm_mm: 40, wall_mm: 9, height_mm: 3.6}\nslicing:\n  layer_height_mm: 1.8\n"
                                     "path:\n  pattern: eulerian\n  bead_width_mm: 5.3\n  overlap_model: existing\n"
                                     "process:\n  travel_speed_mm_min: 400\n  wire_feed_mm_min: 5200\n";
    const PlanResult plan = PlanScenario(analysis::LoadScenario(dir / "j.yaml"), nullptr);
    std::filesystem::remove_all(dir);
    std::vector<Move2D> moves;
    for (const PathPoint& p : plan.plan.layers[0].points) moves.push_back({p.p_P.head<2>(), p.weld});
    const std::vector<Junction> found = FindJunctions(plan.plan.layers[0].slice, moves, 5.3, 3);
    ASSERT_EQ(found.size(), 1u) << arms;
    EXPECT_EQ(found[0].ClassName(), name) << arms;
    // The generator centres the bounding box, which for the symmetric cross is the junction itself.
    if (name.rfind("4 ribs 90", 0) == 0) {
      EXPECT_LT(found[0].centre.norm(), 1e-6) << "the cross's centre";
    }
  }
}

// A bent tube bent tighter than eq. 6.4 allows fails before slicing, naming the generator key.
TEST(SkeletonPlanner, ScenarioBendTighterThanTheRuleIsRefused) {
  const std::filesystem::path file = std::filesystem::path(WAAM_SOURCE_DIR) / "scenarios/tubes/part_1.yaml";
  const analysis::Scenario scenario = analysis::LoadScenario(file, {"part.generator.bend_radius_mm=120"});
  try {
    PlanScenario(scenario, nullptr);
    FAIL() << "PlanScenario must refuse a bend tighter than eq. 6.4 allows";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bent_tube.bend_radius_mm: bend radius 120 mm is tighter than R_min = 150 mm"));
  }
}

}  // namespace
}  // namespace waam::planner
