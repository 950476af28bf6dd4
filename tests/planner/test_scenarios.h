// Small scenarios built in code for the planner and twin tests: a hub-and-blade propeller planned multi-directionally,
// and the files a scenario names loaded as the scenario loader loads them.
#pragma once

#include <memory>

#include "models/core/files.h"
#include "models/fit/model_file.h"
#include "planner/scenario/scenario.h"

namespace waam::planner::testing {

// `s` with what analysis::LoadScenario reads into a scenario from files: the part's STL bytes (when it names a mesh)
// and the default CSW, speed-height and width-height models (models/data).
inline PlannerSections WithFiles(PlannerSections s) {
  if (!s.part.mesh_path.empty()) s.part.mesh_data = std::make_shared<const std::string>(ReadFile(s.part.mesh_path));
  s.process.csw = std::make_shared<const models::CswModel>(models::CswModel::Load(models::DefaultModelPath("csw")));
  s.process.speed_height = std::make_shared<const models::SpeedHeightModel>(
      models::SpeedHeightModel::Load(models::DefaultModelPath("speed_height")));
  s.process.width_height = std::make_shared<const models::WidthHeightModel>(
      models::WidthHeightModel::Load(models::DefaultModelPath("width_height")));
  return s;
}

// A small propeller (hub 60 mm across the flats and 60 mm tall, four blades 40 mm long and 40 mm wide, 16 -> 10 mm
// thick, pitched `pitch_root_deg` -> `pitch_tip_deg` degrees from root to tip), sliced multi-directionally: the hub
// along +z, then each blade along its own radial direction (+x, +y, -x, -y) beyond the hub's flat at 30 mm; contour
// passes, 2.5 mm layers, 6 mm beads, the scenario's default path.retract_mm.
inline PlannerSections SmallPropeller(double pitch_root_deg = 30.0, double pitch_tip_deg = 50.0) {
  PlannerSections s;
  s.name = "propeller";
  s.part.generator = PartGenerator::kPropeller;
  s.part.params = {{"hub_mm", {60.0, 60.0}},
                   {"span_mm", {40.0}},
                   {"chord_mm", {40.0}},
                   {"thickness_mm", {16.0, 10.0}},
                   {"pitch_deg", {pitch_root_deg, pitch_tip_deg}}};
  s.part.where = "test: part.generator";
  s.slicing.type = SlicingType::kMultiDirectional;
  s.slicing.layer_height_mm = 2.5;
  s.slicing.sub_volumes.push_back({"hub", {0, 0, 1}, {{1, 0, 0, 30}, {-1, 0, 0, 30}, {0, 1, 0, 30}, {0, -1, 0, 30}}});
  s.slicing.sub_volumes.push_back({"blade_0", {1, 0, 0}, {{-1, 0, 0, -30}}});
  s.slicing.sub_volumes.push_back({"blade_90", {0, 1, 0}, {{0, -1, 0, -30}}});
  s.slicing.sub_volumes.push_back({"blade_180", {-1, 0, 0}, {{1, 0, 0, -30}}});
  s.slicing.sub_volumes.push_back({"blade_270", {0, -1, 0}, {{0, 1, 0, -30}}});
  s.path.pattern = Pattern::kContour;
  s.path.bead_width_mm = 6.0;
  return s;
}

// The same propeller (pitch 30 -> 50 deg) with arc-off retracts of `retract_mm` mm (0: straight rapids).
inline PlannerSections SmallPropellerWithRetract(double retract_mm) {
  PlannerSections s = SmallPropeller();
  s.path.retract_mm = retract_mm;
  return s;
}

}  // namespace waam::planner::testing
