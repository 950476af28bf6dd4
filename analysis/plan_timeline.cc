// The build's timeline on the scenario's cell and its JSON form.
#include "analysis/plan_timeline.h"

#include "models/core/numbers.h"
#include "planner/kinematics/cell_motion.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::analysis {

planner::Timeline CellTimeline(const Scenario& scenario, const twin::CellModel& cell, const planner::Plan& plan,
                               const std::vector<double>& extra_wait_before_layer_s) {
  const twin::CellSettings& settings = scenario.cell;
  const planner::CellKinematics kin = twin::PartKinematics(cell, settings);
  // The motion `waam check` plans with the fixed spin rule: the positioner kept the joint margin inside its limits.
  planner::CellKinematics solve = kin;
  const double margin_rad = settings.joint_margin_deg / kDeg;
  if (solve.positioner.tilt_upper - solve.positioner.tilt_lower > 2.0 * margin_rad) {
    solve.positioner.tilt_lower += margin_rad;
    solve.positioner.tilt_upper -= margin_rad;
  }
  if (solve.positioner.rotation_upper - solve.positioner.rotation_lower > 2.0 * margin_rad) {
    solve.positioner.rotation_lower += margin_rad;
    solve.positioner.rotation_upper -= margin_rad;
  }
  planner::MotionOptions options;
  options.step_mm = settings.step_mm;
  options.rapid_speed_mm_s = scenario.process.rapid_speed_mm_min / 60.0;
  options.rotation_rad = settings.positioner_rotation_deg / kDeg;
  options.positioner_per_point = settings.positioner_follow == twin::PositionerFollow::kPoint;
  options.tilt_tolerance_rad = settings.positioner_tilt_tolerance_deg / kDeg;
  const std::vector<planner::CellSample> motion = planner::PlanCellMotion(solve, plan, options, {});
  planner::TimelineSettings timing = planner::TimelineSettingsOf(scenario.process);
  timing.extra_wait_before_layer_s = extra_wait_before_layer_s;
  return planner::BuildTimeline(plan, motion, planner::AxisLimitsOf(kin), timing);
}

void AddCellTimeline(const Scenario& scenario, planner::PlanResult* result,
                     const std::vector<double>& extra_wait_before_layer_s) {
  const twin::CellModel cell = twin::LoadCell(scenario.cell);
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
