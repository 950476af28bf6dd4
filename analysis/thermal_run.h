// The thermal run of a build: the plan's timeline drives the thermal model (twin::ThermalSimulation) span by span,
// with interpass waits where process.interpass asks for them, probe histories and a field at each layer's end.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/scenario.h"
#include "planner/path/tool_path.h"
#include "planner/timeline/timeline.h"
#include "twin/thermal/thermal_simulation.h"

namespace waam {
class Progress;
}  // namespace waam

namespace waam::analysis {

// What one layer saw.
struct ThermalLayer {
  int layer = 0;
  double start_s = 0.0;      // its first arc start, s from the program's start (after any interpass wait)
  double end_s = 0.0;        // its last arc end, s
  // Temperature at process.interpass.at just before the layer's first arc start (after the wait), degC; NaN when
  // no metal is there (top_max before the first layer).
  double interpass_c = 0.0;
  double peak_c = 0.0;       // hottest metal from the layer's first arc start to its last arc end (sampled), degC
  // Mean over the layer's weld moves of the metal one grid cell under each move's bead just before the move is welded
  // (the local interpass temperature where its beads are laid), degC; NaN for the first layer and where no metal is.
  double laid_on_c = 0.0;
  double wait_s = 0.0;       // interpass wait added before the layer, s
  bool interpass_reached = true;  // false: the wait was cut at kMaxInterpassWaitS before the limit was reached
};

// A probe's temperature at every sample time (NaN while no metal is there).
struct ThermalProbeHistory {
  std::string name;
  Eigen::Vector3d p_mm = Eigen::Vector3d::Zero();
  std::vector<double> temperature_c;  // one per ThermalRunResult::sample_time_s
  double max_c = 0.0;                 // NaN when never in metal
  double time_of_max_s = 0.0;
};

// The temperature field at one layer's end (its last arc end).
struct ThermalLayerField {
  int layer = 0;
  double time_s = 0.0;
  twin::TemperatureField field;
};

struct ThermalRunResult {
  twin::ThermalSettings settings;          // what was solved: materials, plate and deposit boxes, losses
  planner::Timeline timeline;              // the build's timeline, interpass waits included
  std::vector<ThermalLayer> layers;        // one per plan layer
  std::vector<double> sample_time_s;       // probe sample times, s (every thermal.sample_s, and the end)
  std::vector<ThermalProbeHistory> probes; // in thermal.probes order
  std::vector<ThermalLayerField> fields;   // one per layer with an arc
  twin::EnergyBalance energy;              // the solver's accounts at the end
  double arc_energy_j = 0.0;               // electrical arc energy: power x arc time (arc on, start and end), J
  double heat_w = 0.0;                     // heat into the metal while the arc burns: efficiency x power, W
  twin::ThermalStats stats;
  double wall_s = 0.0;                     // wall-clock time of the thermal solve, s
};

// Longest interpass wait before one layer, s; a limit not reached by then is reported (interpass_reached false).
inline constexpr double kMaxInterpassWaitS = 4.0 * 3600.0;

// The timeline of the plan with `extra_wait_s[layer]` seconds of interpass wait before each layer's first arc start
// (planner::BuildTimeline with the scenario's process and cell).
using TimelineBuilder = std::function<planner::Timeline(const std::vector<double>& extra_wait_s)>;

// The solver's settings for a planned scenario: materials and losses from the thermal section, the plate from
// thermal.substrate (centred under the part, its top at z = 0, unless centre_mm is given), the deposit box from the
// plan's beads. Throws InputError for a probe outside both the plate and the part.
twin::ThermalSettings ThermalSettingsFor(const Scenario& scenario, const planner::Plan& plan);

// The thermal section's settings for a deposit whose beads lie in `beads` (part frame, mm): materials, grid, start
// and boundary temperatures, losses, table, clamps, heat source, the plate's box and the deposit's (one cell beyond
// the beads). ThermalSettingsFor and the replay's model (which then takes the log's ambient and table) both start
// here, so that a key the section resolves reaches both.
twin::ThermalSettings SectionSettings(const ThermalSection& thermal, const Eigen::AlignedBox3d& beads);

// Throws InputError naming `where` (a scenario key) when the probe at `p_mm` lies in neither the plate nor the deposit
// box of `settings`: "KEY = [x, y, z]: outside the plate [...] and the part [...]; a probe must lie in the metal".
void CheckProbeInMetal(const twin::ThermalSettings& settings, const Eigen::Vector3d& p_mm, const std::string& where);

// Runs the thermal model along the plan's timeline: Weld for arc-on spans (heat = process.arc efficiency x power),
// a zero-length Weld for arc start and arc end (the arc burns where the torch stands), Cool for travel, positioner
// and wait spans; before each layer after the first, cools until process.interpass holds. Returns the timeline
// rebuilt with those waits and everything recorded. `progress` (may be null) counts spans. Throws InputError (via
// ThermalSettingsFor) and Interrupted.
ThermalRunResult RunThermalModel(const Scenario& scenario, const planner::Plan& plan, const TimelineBuilder& build,
                                 Progress* progress);

}  // namespace waam::analysis
