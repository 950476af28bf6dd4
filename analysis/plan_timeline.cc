// The build's timeline on the scenario's cell and its JSON form.
#include "analysis/plan_timeline.h"

#include "analysis/cell_files.h"
#include "models/core/numbers.h"
#include "planner/kinematics/cell_motion.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::analysis {

planner::Timeline CellTimeline(const Scenario& scenario, const twin::CellModel& cell, const planner::Plan& plan,
                               const std::vector<double>& extra_wait_before_layer_s) {
  const twin::CellSettings& settings = scenario.cell;
  planner::CellKinematics kin = twin::PartKinematics(cell, settings);
  if (plan.X_FT) kin.X_FT = *plan.X_FT;  // an imported program's own tool is the TCP that moves, as in the check
  // The motion `waam check` plans with the fixed spin rule: the positioner kept the joint margin inside its limits.
  const planner::CellKinematics solve = twin::MarginKinematics(kin, settings);
  const planner::MotionOptions options =
      twin::MotionOptionsOf(settings, scenario.process.rapid_speed_mm_min / 60.0);
  const std::vector<planner::CellSample> motion = planner::PlanCellMotion(solve, plan, options, {});
  planner::TimelineSettings timing = planner::TimelineSettingsOf(scenario.process);
  timing.extra_wait_before_layer_s = extra_wait_before_layer_s;
  return planner::BuildTimeline(plan, motion, planner::AxisLimitsOf(kin), timing);
}

void AddCellTimeline(const Scenario& scenario, planner::PlanResult* result,
                     const std::vector<double>& extra_wait_before_layer_s) {
  const twin::CellModel cell = LoadCell(scenario.cell);
  result->timeline = CellTimeline(scenario, cell, result->plan, extra_wait_before_layer_s);
  result->stats.estimated_time_s = result->timeline.total_s;
}

nlohmann::json TimelineToJson(const planner::Timeline& timeline) {
  nlohmann::json layers = nlohmann::json::array();
  for (const planner::LayerTimes& l : timeline.layers) {
    layers.push_back({{"layer", l.layer},
                      {"start_s", l.start_s},
                      {"end_s", l.end_s},
                      {"arc_on_s", l.arc_on_s},
                      {"travel_s", l.travel_s},
                      {"wait_s", l.wait_s}});
  }
  return {{"total_s", timeline.total_s},
          {"arc_on_s", timeline.arc_on_s},
          {"travel_s", timeline.travel_s},
          {"wait_s", timeline.wait_s},
          {"layers", layers}};
}

}  // namespace waam::analysis
