// Tests of the planning pipeline PlanScenario: layers, heights, bead from the volume balance, mesh errors.
#include "planner/plan_scenario.h"
#include "tests/planner/test_scenarios.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"

namespace waam::planner {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

PlannerSections BoxScenario() {
  PlannerSections s;
  s.name = "box";
  s.part.generator = PartGenerator::kBox;
  s.part.params["size_mm"] = {60, 40, 12};
  s.part.where = "test: part.generator";
  s.slicing.layer_height_mm = 1.5;
  s.path.pattern = Pattern::kContinuous;
  s.path.bead_width_mm = 6.0;
  return s;
}

TEST(PlanScenarioTest, LayersSitOnTheirTopsAndCountMatchesHeight) {
  PlannerSections s = BoxScenario();
  s.path.retract_mm = 0.0;  // every point on its layer (the retracts leave it: retract_test.cc)
  const PlanResult result = PlanScenario(testing::WithFiles(s), nullptr);
  ASSERT_EQ(result.plan.layers.size(), 8u) << "12 mm at 1.5 mm layers";
  for (const LayerPath& layer : result.plan.layers) {
    EXPECT_NEAR(layer.z_mm, 1.5 * (layer.index + 1), 1e-9);
    ASSERT_FALSE(layer.points.empty());
    for (const PathPoint& point : layer.points) EXPECT_DOUBLE_EQ(point.p_P.z(), layer.z_mm);
  }
  EXPECT_EQ(result.stats.passes, result.stats.layers) << "continuous: one weld pass per layer";
}

TEST(PlanScenarioTest, BeadComesFromTheWireFeedVolumeBalance) {
  PlannerSections s = BoxScenario();
  s.process.wire_diameter_mm = 1.2;
  s.process.wire_feed_mm_min = 6000;
  s.process.travel_speed_mm_min = 500;
  s.process.deposition_efficiency = 0.9;
  const PlanResult result = PlanScenario(testing::WithFiles(s), nullptr);
  // eq. 3.4: A v_t = eta * pi d^2 / 4 * v_w.
  const double wire_area = std::numbers::pi * 1.2 * 1.2 / 4.0;
  EXPECT_NEAR(result.bead_area_mm2 * 500.0, 0.9 * wire_area * 6000.0, 1e-9);
  EXPECT_NEAR(2.0 * 6.0 * result.bead_height_mm / 3.0, result.bead_area_mm2, 1e-9) << "A = 2wh/3";
  EXPECT_NEAR(result.layer_growth_mm, result.bead_area_mm2 / (0.738 * 6.0), 1e-9);
  for (const PathPoint& point : result.plan.layers[0].points) {
    EXPECT_DOUBLE_EQ(point.bead_height_mm, result.bead_height_mm);
    EXPECT_DOUBLE_EQ(point.speed_mm_s, 500.0 / 60.0);
  }
}

TEST(PlanScenarioTest, SpeedHeightModeTakesSpeedAndWidthFromTheFittedModels) {
  PlannerSections s = BoxScenario();
  s.process.bead_model = BeadModel::kSpeedHeight;
  s.slicing.layer_height_mm = 1.5;
  const PlanResult result = PlanScenario(testing::WithFiles(s), nullptr);
  // The default fits (models/data, dissertation Table 18 rows 2-17): v = 673.8 h^-2.069, w(1.5 mm) about 5.1 mm.
  EXPECT_NEAR(result.travel_speed_mm_min, 673.847 * std::pow(1.5, -2.06916), 1.0);
  EXPECT_NEAR(result.bead_width_mm, 5.08, 0.1);
  EXPECT_EQ(result.speed_clamp, "none");
  EXPECT_NEAR(result.bead_height_mm, 1.5, 1e-6);
  const PathPoint& point = result.plan.layers[0].points.back();
  EXPECT_DOUBLE_EQ(point.speed_mm_s, result.travel_speed_mm_min / 60.0);
  EXPECT_DOUBLE_EQ(point.bead_width_mm, result.bead_width_mm);
}

TEST(PlanScenarioTest, SpeedHeightModeClampsAHeightOutsideTheWindow) {
  PlannerSections s = BoxScenario();
  s.process.bead_model = BeadModel::kSpeedHeight;
  s.slicing.layer_height_mm = 3.0;  // would need ~70 mm/min, below the 150 mm/min feasible minimum
  const PlanResult result = PlanScenario(testing::WithFiles(s), nullptr);
  EXPECT_EQ(result.speed_clamp, "at_minimum");
  EXPECT_DOUBLE_EQ(result.travel_speed_mm_min, 150.0);
}

TEST(PlanScenarioTest, PartIsPutOnTheSubstrate) {
  // A mesh floating at z = 50 is planned from z = 0.
  const fs::path dir = fs::temp_directory_path() / ("waam_planar_planner_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream stl(dir / "raised.stl");
  stl << "solid raised\n";
  const double v[8][3] = {{0, 0, 50}, {20, 0, 50}, {20, 20, 50}, {0, 20, 50},
                          {0, 0, 56}, {20, 0, 56}, {20, 20, 56}, {0, 20, 56}};
  const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                        {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  for (const auto& facet : f) {
    stl << "facet normal 0 0 0\nouter loop\n";
    for (int k : facet) stl << "vertex " << v[k][0] << " " << v[k][1] << " " << v[k][2] << "\n";
    stl << "endloop\nendfacet\n";
  }
  stl << "endsolid raised\n";
  stl.close();
  PlannerSections s = BoxScenario();
  s.part.generator.reset();
  s.part.mesh_path = dir / "raised.stl";
  const PlanResult result = PlanScenario(testing::WithFiles(s), nullptr);
  EXPECT_EQ(result.plan.layers.size(), 4u);
  EXPECT_NEAR(result.plan.layers.front().z_mm, 1.5, 1e-9);
  EXPECT_NEAR(result.mesh_report.bbox_min.z(), 0.0, 1e-9);
  fs::remove_all(dir);
}

TEST(PlanScenarioTest, UnknownGeneratorIsNamed) {
  try {
    ParsePartGenerator("dodecahedron", "s.yaml:3: part.generator");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("s.yaml:3: part.generator: unknown generator type 'dodecahedron' (known: "));
  }
  EXPECT_EQ(ParsePartGenerator("bent_tube", "s.yaml:3: part.generator"), PartGenerator::kBentTube);
}

TEST(PlanScenarioTest, PartWithoutMeshOrGeneratorIsRefused) {
  PlannerSections s = BoxScenario();
  s.part.generator.reset();
  try {
    PlanScenario(testing::WithFiles(s), nullptr);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("give exactly one of 'mesh' or 'generator'"));
  }
}

}  // namespace
}  // namespace waam::planner
