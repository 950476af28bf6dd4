// The cell check's torch-to-part test along the planned arc-off moves: with straight rapids the torch cuts into a
// sub-volume built earlier, with the planner's retracts (path.retract_mm) it does not.
#include <string>

#include <gtest/gtest.h>

#include "planner/plan_scenario.h"
#include "analysis/cell_files.h"
#include "tests/planner/test_scenarios.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {
namespace {
using analysis::LoadCell;

struct PartHits {
  int weld = 0;    // part collisions whose worst sample is on a weld move
  int travel = 0;  // ... on an arc-off move
  std::string text;
};

// Plans the small propeller of test_scenarios.h (the hub along +z, then each blade along its own radial direction)
// with `retract_mm` mm retracts and checks it on the built-in cell.
PartHits CheckPart(double retract_mm) {
  const planner::PlanResult planned =
      planner::PlanScenario(planner::testing::WithFiles(planner::testing::SmallPropellerWithRetract(retract_mm)), nullptr);
  twin::CellSettings settings;  // the built-in cell, part_collision on
  const CheckReport r = CheckPlan(LoadCell(settings), planned.plan, settings, 100.0, nullptr);
  PartHits hits;
  for (const CheckViolation& v : r.violations) {
    if (v.kind != ViolationKind::kCollision || v.body1 != "part") continue;
    (r.motion[v.sample].weld ? hits.weld : hits.travel) += 1;
    hits.text += "layer " + std::to_string(v.layer) + " point " + std::to_string(v.point) + ": " +
                 std::to_string(v.value) + " mm\n";
  }
  return hits;
}

TEST(RetractCheckTest, StraightRapidsIntoTheBladesCutTheHubAndRetractsDoNot) {
  ASSERT_TRUE(twin::CellSettings{}.part_collision);
  const PartHits rapids = CheckPart(0.0);
  EXPECT_GT(rapids.travel, 0)
      << "a straight rapid from the hub's top to a blade's root must cut the hub (measured: the four rapids into the "
         "blades, 12-25 mm deep)";
  const PartHits retracts = CheckPart(15.0);
  EXPECT_EQ(retracts.travel, 0) << "with 15 mm retracts no arc-off move reaches the metal:\n" << retracts.text;
  EXPECT_EQ(retracts.weld, rapids.weld) << "the weld moves are the same";
}

}  // namespace
}  // namespace waam::twin
