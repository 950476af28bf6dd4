// Tests of the multi-directional hub-and-blade planning (Lim & Soh, seed 002).
#include "planner/multidir_planner.h"
#include "planner/plan_scenario.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "planner/mesh/mesh_ops.h"
#include "tests/planner/test_scenarios.h"

namespace waam::planner {
namespace {
using ::testing::HasSubstr;
using testing::SmallPropeller;

TEST(MultiDirectionalTest, SubVolumesAddUpToThePartAndWeldAlongTheirDirection) {
  const PlanResult result = PlanScenario(testing::WithFiles(SmallPropeller(30, 50)), nullptr);
  ASSERT_EQ(result.sub_volumes.size(), 5u);
  double sum = 0.0;
  for (const SubVolumeReport& sub : result.sub_volumes) {
    sum += sub.volume_mm3;
    ASSERT_GT(sub.layers, 0) << sub.name;
    for (int i = sub.first_layer; i < sub.first_layer + sub.layers; ++i) {
      for (const PathPoint& p : result.plan.layers[i].points) {
        EXPECT_LT((p.tool_dir_P - sub.direction).norm(), 1e-12) << sub.name;
        // Blades weld beyond their split plane (the hub flat at 30 mm), the hub inside the flats.
        if (sub.name != "hub") {
          EXPECT_GT(p.p_P.dot(sub.direction), 30.0) << sub.name;
        }
      }
    }
  }
  const double volume = EnclosedVolume(result.mesh);
  EXPECT_NEAR(sum / volume, 1.0, 0.01) << "slice areas x layer heights against the divergence-theorem volume";
  EXPECT_NEAR(result.sub_volumes[0].support_mm3, 0.0, 1.0) << "the hub prism needs no support";
  EXPECT_GT(result.sub_volumes[1].support_mm3, 0.01 * result.sub_volumes[1].volume_mm3)
      << "a pitched blade overhangs its root when built radially";
}

TEST(MultiDirectionalTest, UnpitchedTaperedBladesNeedNoSupport) {
  // With zero pitch every blade section lies inside the one below it (the thickness only shrinks).
  const PlanResult result = PlanScenario(testing::WithFiles(SmallPropeller(0, 0)), nullptr);
  for (std::size_t k = 1; k < result.sub_volumes.size(); ++k) {
    EXPECT_LT(result.sub_volumes[k].support_mm3, 1e-3 * result.sub_volumes[k].volume_mm3)
        << result.sub_volumes[k].name;
  }
}

TEST(MultiDirectionalTest, ASubVolumeWithoutMetalIsNamed) {
  PlannerSections s = SmallPropeller(30, 50);
  s.slicing.sub_volumes.push_back({"nothing", {0, 0, 1}, {{0, 0, -1, -500}}});
  try {
    PlanScenario(testing::WithFiles(s), nullptr);
    FAIL() << "expected an InputError for a sub-volume above the part";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("'nothing' holds no metal"));
  }
}

}  // namespace
}  // namespace waam::planner
