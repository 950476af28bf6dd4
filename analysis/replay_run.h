// The replay of a process log: the logged arc drives the thermal model (twin::ThermalSimulation) row by row, the
// thermocouples are compared with the simulated temperatures at their places (docs/REPLAY.md).
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/replay_log.h"
#include "analysis/scenario.h"
#include "twin/thermal/thermal_simulation.h"

namespace waam::analysis {

// The uncertain parameters of the thermal model, those `waam fit thermal` may move.
struct ThermalParameters {
  double efficiency = 0.84;               // arc efficiency: heat into the metal / electrical power, 1
  double convection_w_m2k = 10.0;         // h on every exposed face, W/(m^2 K)
  double table_conductance_w_m2k = 0.0;   // plate-table contact, W/(m^2 K)
  double emissivity = -1.0;               // of every exposed face; < 0 = each material's own
  double clamp_factor = 1.0;              // every clamp's conductance_w_m2k times this (thermal.clamps[]), 1
  bool operator==(const ThermalParameters&) const = default;
};

// Everything a replay needs, resolved from the scenario and the log.
struct ReplayModel {
  twin::ThermalSettings settings;   // plate, deposit box (from the arc-on head path), materials, losses
  ThermalParameters parameters;     // the scenario's values (process.arc.efficiency, thermal.*)
  ReplayLog log;
  std::vector<ReplayProbe> probes;  // replay.probes, in file order
  std::vector<double> clamp_w_m2k;  // each clamp's conductance_w_m2k as the scenario gives it (factor 1), W/(m^2 K)
  double bead_width_mm = 6.0;
  double bead_height_mm = 2.0;
};

// The solver's settings and the log together. The deposit box is what the arc-on moves lay (the bead below the
// head, half its width around it) plus one cell; the plate is thermal.substrate (centred under that box with its top
// at z = 0 unless centre_mm is given). Throws InputError for a probe outside both the plate and that box (naming
// replay.probes.NAME.at_mm).
ReplayModel MakeReplayModel(const Scenario& scenario, ReplayLog log);

// The simulated temperature of each probe at each row's time, degC (NaN where no metal is yet, and after end_s).
struct ReplaySimulation {
  std::vector<std::vector<double>> probe_c;  // [probe][row]
  twin::EnergyBalance energy;
  twin::ThermalStats stats;
  double heat_input_j = 0.0;                 // efficiency x logged arc energy replayed, J
  double wall_s = 0.0;
};

// A replay that can be continued: AdvanceTo drives the rows not yet driven up to a time, Result reads every row
// driven so far. A replay advanced to A and then to B gives the rows up to A as one advanced to A alone, and the rows
// after A as a replay to B up to the solver's tolerance (reading at A ends the solver's multirate batch there).
class ReplayRun {
 public:
  // Throws InputError for parameters out of range (naming them). `model` must outlive the run.
  ReplayRun(const ReplayModel& model, const ThermalParameters& parameters);
  // Drives the rows with time_s <= end_s (see SimulateReplay). Throws Interrupted on Ctrl-C.
  void AdvanceTo(double end_s);
  // Drives the rows with time_s <= end_s, and after them as many rows as the solver needs to solve the batch holding
  // the last of them by itself (at most its top level's step, ThermalSettings::whole_step_s, further), instead of
  // ending that batch at end_s: the probes up to end_s are then those of the whole log's replay, and the run goes
  // on as that one does (docs/REPLAY.md, "The window and held-out rows"). Throws Interrupted on Ctrl-C.
  void AdvanceThrough(double end_s);
  // The probes (degC, by probe and row) at the rows with time_s <= end_s, NaN at the others, solving nothing held
  // back when AdvanceThrough(end_s) drove them (else the held-back motion first, as Result).
  std::vector<std::vector<double>> ProbesTo(double end_s) const;
  // The probes at every row driven so far (NaN at the rows after them), the energy, stats and wall time.
  ReplaySimulation Result() const;
  const ThermalParameters& parameters() const { return parameters_; }
  // The solver's choices (twin::ThermalSimulation::RecordChoices and FollowChoices; docs/THERMAL.md, "Differencing
  // a run"): record or follow them from the first AdvanceTo on; TakeChoices after Result.
  void RecordChoices() { sim_.RecordChoices(); }
  twin::SolverChoices TakeChoices() { return sim_.TakeChoices(); }
  void FollowChoices(std::shared_ptr<const twin::SolverChoices> choices) { sim_.FollowChoices(std::move(choices)); }

 private:
  const ReplayModel* model_;
  ThermalParameters parameters_;
  twin::ThermalSimulation sim_;
  std::size_t next_row_ = 0;
  std::vector<std::size_t> records_;  // the solver's probe record of each row driven
  double heat_input_j_ = 0.0;
  double wall_s_ = 0.0;
};

// Drives the model through the rows with time_s <= end_s: between two rows the arc (when the first row has it on
// and no gap follows) welds along the head's straight move with power x efficiency of the first row, else the part
// cools; measured ambient and table temperatures (when logged) hold from their row. Throws InputError for
// parameters out of range (naming them) and Interrupted on Ctrl-C.
ReplaySimulation SimulateReplay(const ReplayModel& model, const ThermalParameters& parameters,
                                double end_s = std::numeric_limits<double>::infinity());

// Measured against simulated over the rows with time in [from_s, to_s]; rows where either is NaN are left out.
struct ReplayErrors {
  std::size_t n = 0;                 // rows compared
  double rmse_c = 0.0, mae_c = 0.0;  // degC
  double mape_pct = 0.0;             // mean |error| / |measured| in percent (rows with |measured| >= 1 degC)
  double max_error_c = 0.0, max_error_time_s = 0.0;  // largest |simulated - measured| and when, degC, s
  double peak_measured_c = 0.0, peak_measured_time_s = 0.0;
  double peak_simulated_c = 0.0, peak_simulated_time_s = 0.0;
};

// The errors of every probe (probes.<NAME>) and of all of them together (overall) over [from_s, to_s] (with
// `outside`, over the rows outside it: a fit's held-out rows), as replay.json and the fitted file write them.
nlohmann::json ReplayErrorsJson(const ReplayModel& model, const ReplaySimulation& simulation, double from_s,
                                double to_s, bool outside = false);
ReplayErrors CompareProbe(const std::vector<double>& time_s, const std::vector<double>& measured,
                          const std::vector<double>& simulated, double from_s, double to_s, bool outside = false);

// A window "A:B" of seconds from the log's first row. Throws InputError naming `what` (e.g. "--window") unless
// A < B and both lie within [0, the log's last time].
std::pair<double, double> ParseLogWindow(const std::string& text, const ReplayLog& log, const std::string& what);

}  // namespace waam::analysis
