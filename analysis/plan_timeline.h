// The build's timeline on the scenario's cell (planner/timeline over the cell's motion) and its JSON form.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/scenario.h"
#include "planner/planar_planner.h"
#include "planner/timeline/timeline.h"

namespace waam::twin {
class CellModel;
}  // namespace waam::twin

namespace waam::analysis {

// The timeline of `plan` on `cell` (made by LoadCell(scenario.cell)): the cell's motion along the plan as `waam
// check` plans it with the fixed torch spin (positioner limits kept cell.checks.joint_margin_deg inside), the axes'
// speeds and accelerations (cell.axis_ramp_s), the process's arc start/end, rapid speed and interpass keys, and
// `extra_wait_before_layer_s` (per plan layer, s >= 0; e.g. the thermal model's interpass waits). Throws InputError
// for a negative extra wait.
planner::Timeline CellTimeline(const Scenario& scenario, const twin::CellModel& cell, const planner::Plan& plan,
                               const std::vector<double>& extra_wait_before_layer_s = {});

// Loads the scenario's cell and replaces result->timeline by CellTimeline; stats.estimated_time_s becomes its total.
void AddCellTimeline(const Scenario& scenario, planner::PlanResult* result,
                     const std::vector<double>& extra_wait_before_layer_s = {});

// The `timeline` object of plan.json: total_s, arc_on_s, travel_s, wait_s, and layers[] of {layer, start_s, end_s,
// arc_on_s, travel_s, wait_s} (s from the program's start; docs/TIMELINE.md).
nlohmann::json TimelineToJson(const planner::Timeline& timeline);

}  // namespace waam::analysis
