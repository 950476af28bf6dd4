// Tests of the plan size limits: too many layers, too long a weld path and too many points end in one clear error.
#include "planner/plan_limits.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "models/core/error.h"
#include "planner/mesh/generators.h"
#include "analysis/stl_file.h"
#include "planner/plan_scenario.h"
#include "tests/planner/test_scenarios.h"

namespace waam::planner {
namespace {
using ::testing::HasSubstr;

PlannerSections LimitsBox(double x, double y, double z, double layer_height_mm) {
  PlannerSections s;
  s.name = "limits";
  s.part.generator = PartGenerator::kBox;
  s.part.params["size_mm"] = {x, y, z};
  s.part.where = "s.yaml:3: part";
  s.slicing.layer_height_mm = layer_height_mm;
  s.path.pattern = Pattern::kZigzag;
  s.path.bead_width_mm = 6.0;
  return s;
}

std::string LimitsErrorOf(const PlannerSections& s) {
  try {
    PlanScenario(testing::WithFiles(s), nullptr);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(PlanLimitsTest, TooManyLayersIsRefusedBeforeSlicing) {
  // A 10 m tall column (an STL, since the generators stop at 5 m) at 0.05 mm: 200 000 layers.
  TriangleMesh column = GeneratePart("box", {{"size_mm", {10, 10, 5000}}}, "test");
  for (Eigen::Vector3d& v : column.vertices) v.z() *= 2.0;
  const std::filesystem::path stl = std::filesystem::path(::waam_test_env::TempDir()) / "waam_plan_limits_column.stl";
  analysis::WriteStlBinary(column, stl);
  PlannerSections s = LimitsBox(10, 10, 10, 0.05);
  s.part.generator.reset();
  s.part.params.clear();
  s.part.mesh_path = stl;
  EXPECT_THAT(LimitsErrorOf(s), HasSubstr("s.yaml:3: part: the part is 10000 mm tall: 200000 layers at "
                                    "slicing.layer_height_mm = 0.05 mm, more than the limit of 100000"));
  EXPECT_NO_THROW(CheckLayerCount(5000.0, 0.05, "x")) << "exactly the limit is accepted";
  std::filesystem::remove(stl);
}

TEST(PlanLimitsTest, TooLongAWeldPathIsRefusedBeforePlanning) {
  // 5 m x 5 m x 1.5 m block at 1.5 mm layers: 1000 layers of 25 m^2 at a ~4.4 mm spacing, about 5600 km.
  const std::string message = LimitsErrorOf(LimitsBox(5000, 5000, 1500, 1.5));
  EXPECT_THAT(message, HasSubstr("s.yaml:3: part: the plan needs about "));
  EXPECT_THAT(message, HasSubstr("km of weld path"));
  EXPECT_THAT(message, HasSubstr("more than the limit of 100 km"));
}

TEST(PlanLimitsTest, PathPointsPastTheLimitNameTheLayer) {
  EXPECT_NO_THROW(CheckPathPoints(kMaxPathPoints, 7, "p"));
  try {
    CheckPathPoints(kMaxPathPoints + 1, 7, "s.yaml:3: part");
    FAIL() << "expected InputError past kMaxPathPoints";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("s.yaml:3: part: the path has more than 20000000 points by layer 8"));
  }
}

}  // namespace
}  // namespace waam::planner
