// Internal to `waam fit thermal`: its free parameters, the replays' residuals, and one stage of the fit (Ceres on one
// grid, its Jacobians differenced over whole replays).
#pragma once

#include <atomic>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <ceres/ceres.h>

#include "analysis/fit_internal.h"
#include "analysis/replay_run.h"

namespace waam::analysis::internal {

// A free parameter: its name on the command line, its member, its scale and its bounds.
struct FreeParameter {
  std::string name;
  double ThermalParameters::*member;
  double scale;       // x = value / scale, so every x is of order 1
  double lo, hi;      // bounds of the value (hi = +inf: a lower bound only)
  std::string set;    // the scenario key it belongs to (--set)
  // Ceres' variable u for this parameter: x = map.ToScaled(u) (logistic between two bounds, exp above one).
  ParameterMap map() const { return {lo / scale, hi / scale}; }
};

// Every parameter `--free` may name, in the order of the docs.
const std::vector<FreeParameter>& AllThermalFree();
// The free parameters named. Throws InputError for an unknown name, one given twice, or none.
std::vector<FreeParameter> ResolveThermalFree(const std::vector<std::string>& names);
// Scaled values x of Ceres' variables u (n = free.size()), and back.
std::vector<double> ToScaled(const std::vector<FreeParameter>& free, const double* u);
std::vector<double> ToFree(const std::vector<FreeParameter>& free, const std::vector<double>& x);

// Whether two parameter sets are the same (each of AllThermalFree's values within 1e-12 of the other's: a value
// mapped to Ceres' scaled variable and back may differ in its last bits).
bool SameParameters(const ThermalParameters& a, const ThermalParameters& b);

// The residuals of one replay to the window's end: simulated - measured at every compared row, degC.
class ReplayResiduals {
 public:
  // The rows compared: measured inside `window` (s). `model` must outlive this.
  ReplayResiduals(const ReplayModel& model, const std::vector<FreeParameter>& free, const ThermalParameters& start,
                  std::pair<double, double> window);
  std::size_t size() const { return used_.size(); }
  std::size_t free_count() const { return free_.size(); }
  const FreeParameter& free(std::size_t k) const { return free_[k]; }
  const std::vector<FreeParameter>& free() const { return free_; }
  const ReplayModel& model() const { return *model_; }
  // The same rows on another grid of the same log (a coarse stage).
  ReplayResiduals OnModel(const ReplayModel& model) const { return ReplayResiduals(model, free_, start_, window_); }
  // The parameters at scaled values `x` (within the bounds).
  ThermalParameters Parameters(const double* x) const;
  // One replay to the window's end at scaled values `x` into `residuals` (size()). Returns how many compared rows the replay has no temperature at (NaN: no metal at the
  // probe yet, which the log alone decides; a replay that blows up has more). Throws as ReplayRun. With `record`,
  // the solver's choices are recorded there; with `follow`, the replay makes those instead of its own.
  std::size_t Run(const double* x, double* residuals, twin::SolverChoices* record = nullptr,
                  std::shared_ptr<const twin::SolverChoices> follow = nullptr) const;
  int replays() const { return replays_.load(); }
  // Keep the replays Run makes recording its choices, for WholeLogAt (off by default: each holds a simulation): the
  // first, when made at the start values, continued to the log's end at once (its result kept), and the last
  // kRecentRuns others.
  void KeepRuns() const { keep_runs_ = true; }
  // The whole log replayed at `p`: a kept replay made at `p` (SameParameters), continued from where the window's
  // replay stopped, else a fresh replay. Either is the replay `waam thermal replay` makes: a replay of the window
  // drives the log until the solver's own batches hold the window's end (ReplayRun::AdvanceThrough).
  ReplaySimulation WholeLogAt(const ThermalParameters& p) const;

 private:
  const ReplayModel* model_;
  std::vector<FreeParameter> free_;
  ThermalParameters start_;
  std::pair<double, double> window_;
  std::vector<std::pair<std::size_t, std::size_t>> used_;  // (probe, row)
  mutable std::atomic<int> replays_{0};
  static constexpr std::size_t kRecentRuns = 2;  // the point Ceres ends at, and its last trial when that failed
  mutable bool keep_runs_ = false;
  mutable std::unique_ptr<ReplaySimulation> start_whole_;  // the whole log at the start values (KeepRuns)
  mutable std::vector<std::unique_ptr<ReplayRun>> recent_runs_;  // the last recording replays, oldest first
};

// One stage of the fit: Ceres on one grid, from `x` (scaled values), run once or more (a run that ends on the coarse
// stage's seed Jacobian is run again from a differenced one: fit_thermal_cost.cc).
struct StageOutcome {
  std::vector<double> x;                        // the answer, scaled values
  std::vector<ceres::Solver::Summary> runs;     // every Ceres run, in order
  bool usable = false;                          // the last run's IsSolutionUsable()
  std::string termination;                      // CONVERGENCE, NO_CONVERGENCE (iterations spent), FAILURE...
  std::string message;                          // the last run's message, or why the stage stopped
  std::string error;                            // why a replay failed (empty: none did)
  std::vector<double> jacobian;                 // the last one Ceres used, in x, m x n row-major
  std::vector<double> jacobian_at_x;            // the one at the stage's answer x, in x
  bool differenced_at_x = false;                // jacobian_at_x was differenced on this grid at x
  bool coarse_at_x = false;                     // jacobian_at_x was differenced on `jacobian_grid` at x
  double data_cost = 0.0;                       // the final cost without the prior's part
  double function_tolerance = 0.0;              // Ceres' relative tolerance on a change of cost (from the noise)
  int differenced = 0, seeded = 0, coarse = 0;  // the Jacobians Ceres was given, by kind (coarse: on `jacobian_grid`)
  std::vector<std::string> held;                // free parameters held at a bound when the stage ended
  int replays = 0;
  int coarse_replays = 0;                       // replays on `jacobian_grid`
  double seconds = 0.0;                         // wall
};

// Runs a stage with at most `max_iterations` Ceres iterations over all its runs; `seed`: a Jacobian in x (m x n) for
// the first point instead of differences; `prior`: the weak prior's weight W (0: none) and x0, the start's scaled
// values it pulls toward; `progress`: where to write one line per Ceres iteration (null: nowhere);
// `jacobian_grid`: the same rows on a coarser grid, on which the Jacobians are differenced; a run of Ceres that
// converges on them ends the stage, one that ends on a step it could not resolve goes on with Jacobians on the
// stage's own grid (null: always on the stage's grid). Throws Interrupted on Ctrl-C.
StageOutcome SolveStage(const ReplayResiduals& residuals, const std::vector<double>& x_start, int max_iterations,
                        std::vector<double> seed, std::pair<double, std::vector<double>> prior,
                        std::ostream* progress, const ReplayResiduals* jacobian_grid = nullptr);

// The stage's solver record for fitted.json (docs/REPLAY.md, `solver`).
nlohmann::json StageSolverJson(const StageOutcome& stage);

}  // namespace waam::analysis::internal
