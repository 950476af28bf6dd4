// The cell check's torch-to-part test along the planned arc-off moves: with straight rapids the torch cuts into a
// sub-volume built earlier, with the planner's retracts (path.retract_mm) it does not.
#include <string>

#include <gtest/gtest.h>

#include "planner/planar_planner.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {
namespace {

// A small propeller (hub 60 mm across the flats and 60 mm tall, four 40 mm blades) built as the hub along +z, then
// each blade along its own radial direction, on the built-in cell.
planner::Scenario SmallPropeller(double retract_mm) {
  planner::Scenario s;
  s.name = "propeller";
  s.part.generator = "propeller";
  s.part.params = {{"hub_mm", {60.0, 60.0}},
                   {"span_mm", {40.0}},
                   {"chord_mm", {40.0}},
                   {"thickness_mm", {16.0, 10.0}},
                   {"pitch_deg", {30.0, 50.0}}};
  s.part.where = "test: part.generator";
  s.slicing.type = "multi_directional";
  s.slicing.layer_height_mm = 2.5;
  s.slicing.sub_volumes.push_back({"hub", {0, 0, 1}, {{1, 0, 0, 30}, {-1, 0, 0, 30}, {0, 1, 0, 30}, {0, -1, 0, 30}}});
  s.slicing.sub_volumes.push_back({"blade_0", {1, 0, 0}, {{-1, 0, 0, -30}}});
  s.slicing.sub_volumes.push_back({"blade_90", {0, 1, 0}, {{0, -1, 0, -30}}});
  s.slicing.sub_volumes.push_back({"blade_180", {-1, 0, 0}, {{1, 0, 0, -30}}});
  s.slicing.sub_volumes.push_back({"blade_270", {0, -1, 0}, {{0, 1, 0, -30}}});
  s.path.pattern = "contour";
  s.path.bead_width_mm = 6.0;
  s.path.retract_mm = retract_mm;
  return s;
}

struct PartHits {
  int weld = 0;    // part collisions whose worst sample is on a weld move
  int travel = 0;  // ... on an arc-off move
  std::string text;
};

PartHits CheckPart(double retract_mm) {
  const planner::PlanResult planned = planner::PlanScenario(SmallPropeller(retract_mm), nullptr);
  planner::CellSettings settings;  // the built-in cell, part_collision on
  MujocoCell cell(settings.mjcf);
  const CheckReport r = CheckPlan(cell, planned.plan, settings, 100.0, nullptr);
  PartHits hits;
  for (const CheckViolation& v : r.violations) {
    if (v.kind != "collision" || v.body1 != "part") continue;
    (r.motion[v.sample].weld ? hits.weld : hits.travel) += 1;
    hits.text += "layer " + std::to_string(v.layer) + " point " + std::to_string(v.point) + ": " +
                 std::to_string(v.value) + " mm\n";
  }
  return hits;
}

TEST(RetractCheckTest, StraightRapidsIntoTheBladesCutTheHubAndRetractsDoNot) {
  ASSERT_TRUE(planner::CellSettings{}.part_collision);
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
