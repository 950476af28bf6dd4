// `waam fit thermal`: Ceres moves the free thermal parameters until the replayed thermocouples match the measured
// ones inside a window of the log; the rest of the log is predicted (held out).
#include <chrono>
#include <cmath>
#include <ctime>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>

#include "analysis/fit_command.h"
#include "analysis/fit_internal.h"
#include "analysis/fit_thermal_cost.h"
#include "analysis/replay_command.h"
#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis {

namespace {

// Where a stage writes its line per Ceres iteration: stderr, with the progress bars (none with --quiet).
std::ostream* IterationLog(const FitOptions& options) { return options.quiet ? nullptr : &std::cerr; }

using internal::FreeParameter;
using internal::ReplayResiduals;
using internal::StageOutcome;

// `--set` lines that make a scenario use `p` (emissivity only when set, the clamp factor only when not 1).
nlohmann::json SetLines(const ThermalParameters& p) {
  nlohmann::json lines = nlohmann::json::array();
  for (const FreeParameter& f : internal::AllThermalFree()) {
    const double v = p.*(f.member);
    if ((f.name == "emissivity" && v < 0.0) || (f.name == "clamps" && v == 1.0)) continue;
    std::ostringstream s;
    s << f.set << "=" << std::setprecision(8) << v;
    lines.push_back(s.str());
  }
  return lines;
}

nlohmann::json ThermalValuesJson(const std::vector<FreeParameter>& free, const ThermalParameters& p) {
  nlohmann::json j = nlohmann::json::object();
  for (const FreeParameter& f : free) j[f.name] = p.*(f.member);
  return j;
}

// The start values of a fit: the model's parameters, where a free emissivity starts from the deposit's own (the
// scenario's < 0 means "each material's").
ThermalParameters FitStart(const ReplayModel& model, const std::vector<FreeParameter>& free) {
  ThermalParameters start = model.parameters;
  if (start.emissivity < 0.0) {
    for (const FreeParameter& f : free) {
      if (f.name == "emissivity") start.emissivity = model.settings.deposit.emissivity;
    }
  }
  return start;
}

// The scenario's replay model on a grid of `cell_mm` (the options' other --set lines kept), its solver settings
// checked there (the grid must hold the solver's reaches) before any replay, and named by `option`.
ReplayModel ModelOnGrid(const FitOptions& options, double cell_mm, const char* option) {
  std::vector<std::string> overrides = options.overrides;
  std::ostringstream cell;
  cell << "thermal.cell_mm=" << std::setprecision(17) << cell_mm;
  overrides.push_back(cell.str());
  ReplayModel model = LoadReplayModel(options.data, overrides, options.start);
  try {
    twin::CheckThermalSettings(model.settings);
  } catch (const InputError& e) {
    WAAM_THROW_UNLESS(false, option << " " << cell_mm << " mm: " << e.what());
  }
  return model;
}

// The rows of the fit on the --jacobian-cell grid, with the model they replay.
struct JacobianGrid {
  JacobianGrid(ReplayModel m, const std::vector<FreeParameter>& free, const ThermalParameters& start,
               std::pair<double, double> window)
      : model(std::move(m)), residuals(model, free, start, window) {}
  ReplayModel model;
  ReplayResiduals residuals;
};

// --jacobian-cell auto: this many times thermal.cell_mm (on the round trip the 3 mm grid's Jacobian columns lie
// within 7 % of the 2 mm grid's and the fit took the same steps; the 4 mm grid's within 11 %, and its steps failed:
// docs/REPLAY.md, "Jacobians on a coarser grid") ...
constexpr double kAutoJacobianFactor = 1.5;
// ... where that grid holds the bead's width and the plate's thickness in at least this many cells.
constexpr double kAutoJacobianCells = 2.0;

// Why the --jacobian-cell auto grid of `mm` does not hold the part (empty: it does).
std::string AutoJacobianGridShortfall(const ReplayModel& model, double mm) {
  std::ostringstream why;
  why << std::setprecision(3);
  const double plate_mm = model.settings.substrate_box_mm.sizes().z();
  if (model.bead_width_mm < kAutoJacobianCells * mm) {
    why << "the bead's " << model.bead_width_mm << " mm width";
  } else if (plate_mm < kAutoJacobianCells * mm) {
    why << "the plate's " << plate_mm << " mm thickness";
  } else {
    return "";
  }
  why << " is under " << kAutoJacobianCells << " cells of " << mm << " mm";
  return why.str();
}

// The --jacobian-cell grid (null: the scenario's), checked before any replay: coarser than the scenario's grid and
// able to hold the solver's reaches. With auto (options.jacobian_cell_mm < 0), kAutoJacobianFactor times the
// scenario's grid where that grid holds the part and the solver's reaches, else the scenario's; `note` says which.
std::unique_ptr<const JacobianGrid> MakeJacobianGrid(const FitOptions& options, const ReplayModel& model,
                                                     const std::vector<FreeParameter>& free,
                                                     const ThermalParameters& start, std::pair<double, double> window,
                                                     std::string* note) {
  std::ostringstream say;
  say << std::setprecision(3);
  if (options.jacobian_cell_mm < 0.0) {
    const double mm = kAutoJacobianFactor * model.settings.cell_mm;
    std::string shortfall = AutoJacobianGridShortfall(model, mm);
    std::unique_ptr<const JacobianGrid> grid;
    if (shortfall.empty()) {
      try {
        grid = std::make_unique<const JacobianGrid>(ModelOnGrid(options, mm, "a grid of"), free, start,
                                                    window);
      } catch (const InputError& e) {
        shortfall = e.what();
      }
    }
    if (grid != nullptr) {
      say << "  Jacobians on a " << mm << " mm grid, the residuals on the scenario's " << model.settings.cell_mm
          << " mm (--jacobian-cell auto; 0: every Jacobian on the scenario's grid)\n";
    } else {
      say << "  Jacobians on the scenario's grid (--jacobian-cell auto: " << shortfall << ")\n";
    }
    *note = say.str();
    return grid;
  }
  const double mm = options.jacobian_cell_mm;
  WAAM_THROW_UNLESS(mm == 0.0 || mm > model.settings.cell_mm,
                    "--jacobian-cell " << mm << " mm: must be auto, 0 (the scenario's grid) or larger than "
                                       << "thermal.cell_mm (" << model.settings.cell_mm << " mm)");
  if (mm == 0.0) return nullptr;
  return std::make_unique<const JacobianGrid>(ModelOnGrid(options, mm, "--jacobian-cell"), free, start, window);
}

// Coarse to fine: the same fit on a grid of --coarse-cell mm first (about 8 times fewer cells at twice the spacing);
// when usable, its answer replaces x and its Jacobian becomes seed, to start the fit on the scenario's grid, which
// alone decides the fitted values. Returns the stage's record for fit.json (null without a coarse stage).
nlohmann::json RunCoarseStage(const FitOptions& options, const ReplayModel& model, const ReplayResiduals& residuals,
                              const std::vector<FreeParameter>& free, std::vector<double>& x,
                              std::vector<double>& seed, std::ostream& out) {
  const double coarse_mm = options.coarse_cell_mm;
  WAAM_THROW_UNLESS(coarse_mm == 0.0 || coarse_mm > model.settings.cell_mm,
                    "--coarse-cell " << coarse_mm << " mm: must be 0 (no coarse stage) or larger than thermal.cell_mm ("
                                     << model.settings.cell_mm << " mm)");
  if (coarse_mm <= model.settings.cell_mm) return nullptr;
  const ReplayModel coarse_model = ModelOnGrid(options, coarse_mm, "--coarse-cell");
  const ReplayResiduals coarse = residuals.OnModel(coarse_model);
  std::vector<double> x0 = x;
  const StageOutcome stage =
      internal::SolveStage(coarse, x, options.max_iterations, {}, {options.prior_weight, x0}, IterationLog(options));
  const bool usable = stage.usable && stage.error.empty();
  if (usable) x = stage.x, seed = stage.jacobian;
  const ThermalParameters reached = coarse.Parameters(stage.x.data());
  out << "  coarse " << coarse_mm << " mm:" << std::setprecision(5);
  for (const FreeParameter& f : free) out << " " << f.name << " " << reached.*(f.member);
  const nlohmann::json solver = internal::StageSolverJson(stage);
  out << " (" << solver["iterations"].get<int>() << " iterations, " << stage.replays << " replays, " << stage.seconds
      << " s" << (usable ? "" : "; not used: " + stage.message + stage.error) << ")\n";
  return {{"cell_mm", coarse_mm},
          {"fitted", ThermalValuesJson(free, reached)},
          {"used", usable},
          {"termination", stage.termination},
          {"iterations", solver["iterations"]},
          {"replays", stage.replays},
          {"time_s", stage.seconds}};
}

// The fit's record without its timings: the values, those that ended on a bound, the errors of the fitted and the
// start runs over the window and the held-out rest of the log, and the solver's record `solver`.
nlohmann::json ThermalFitDoc(const ReplayModel& model, const std::vector<FreeParameter>& free,
                             const ThermalParameters& start, const ThermalParameters& fitted,
                             const ReplaySimulation& start_run, const ReplaySimulation& fitted_run,
                             const std::pair<double, double>& window, const nlohmann::json& solver) {
  nlohmann::json doc;
  doc["parameters"] = ThermalParametersJson(fitted);
  doc["set"] = SetLines(fitted);
  doc["free"] = nlohmann::json::array();
  for (const FreeParameter& f : free) doc["free"].push_back(f.name);
  // A value that ended at its bound (the map reaches it only in the limit: within 1 % of its scale) is a fit the
  // bounds decided, not the data: listed, and said on stdout.
  doc["at_bound"] = nlohmann::json::array();
  for (const FreeParameter& f : free) {
    const double v = fitted.*(f.member);
    const double near = internal::kStartInside * f.scale;
    if (v <= f.lo + near || v >= f.hi - near) doc["at_bound"].push_back(f.name);
  }
  doc["start"] = ThermalValuesJson(free, start);
  doc["fitted"] = ThermalValuesJson(free, fitted);
  doc["window"] = ReplayErrorsJson(model, fitted_run, window.first, window.second);
  doc["held_out"] = ReplayErrorsJson(model, fitted_run, window.first, window.second, true);
  doc["start_window"] = ReplayErrorsJson(model, start_run, window.first, window.second)["overall"];
  doc["start_held_out"] = ReplayErrorsJson(model, start_run, window.first, window.second, true)["overall"];
  doc["solver"] = solver;
  return doc;
}

// The fit's summary on stdout: start and fitted values, bound notes, the rmse of window and held-out part.
void PrintThermalFit(const std::vector<FreeParameter>& free, const ThermalParameters& start,
                     const ThermalParameters& fitted, const nlohmann::json& doc, std::size_t iterations,
                     int replays, double seconds, std::ostream& out) {
  out << std::setprecision(5);
  for (const FreeParameter& f : free) {
    out << "  " << std::left << std::setw(11) << f.name << std::right << " start " << start.*(f.member)
        << "  fitted " << fitted.*(f.member) << "\n";
  }
  for (const auto& name : doc["at_bound"]) {
    out << "  note: " << name.get<std::string>() << " ended at its bound: the data would move it further\n";
  }
  auto rmse = [](const nlohmann::json& j) { return j["overall"]["rmse_c"].dump(); };
  out << "  window   rmse " << rmse(doc["window"]) << " degC (start " << doc["start_window"]["rmse_c"].dump()
      << ")\n  held out rmse " << rmse(doc["held_out"]) << " degC (start " << doc["start_held_out"]["rmse_c"].dump()
      << ")\n  solver   Ceres " << doc["solver"]["termination"].get<std::string>() << ", " << iterations
      << " iterations, " << replays << " replays";
  if (doc["jacobian_cell_mm"].is_number()) {
    out << " (Jacobians: " << doc["solver"]["coarse_replays"].get<int>() << " more on the "
        << doc["jacobian_cell_mm"].get<double>() << " mm grid)";
  }
  out << ", " << seconds << " s\n";
}

// The identifiability report of the fine stage's answer (null when Ceres made no Jacobian there).
nlohmann::json IdentifiabilityJson(const ReplayResiduals& residuals, const ThermalParameters& fitted,
                                   const StageOutcome& fine, double prior_weight) {
  internal::IdentifiabilityInput in;
  for (std::size_t k = 0; k < residuals.free_count(); ++k) {
    const FreeParameter& f = residuals.free(k);
    in.names.push_back(f.name);
    in.scales.push_back(f.scale);
    in.values.push_back(fitted.*(f.member));
  }
  in.m = residuals.size();
  if (fine.jacobian_at_x.size() != in.m * in.names.size()) return nullptr;
  in.jacobian = fine.jacobian_at_x;
  in.data_cost = fine.data_cost;
  in.prior_weight = prior_weight;
  return internal::ThermalIdentifiability(in);
}

}  // namespace

FitOutcome internal::RunFitThermal(const FitOptions& options, std::ostream& out) {
  const auto clock_start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  const std::vector<FreeParameter> free = internal::ResolveThermalFree(options.free);
  WAAM_THROW_UNLESS(options.max_iterations >= 1 && options.max_iterations <= 1000,
                    "--max-iter = " << options.max_iterations << ": must be in [1, 1000]");
  WAAM_THROW_UNLESS(std::isfinite(options.prior_weight) && options.prior_weight >= 0.0,
                    "--prior = " << options.prior_weight << ": must be a weight >= 0 degC (0: no prior)");
  WAAM_THROW_UNLESS(!options.window.empty(), "--window START:END is required: the part of the log fitted, in s");
  const ReplayModel model = LoadReplayModel(options.data, options.overrides, options.start);
  const std::pair<double, double> window = ParseLogWindow(options.window, model.log, "--window");
  for (const FreeParameter& f : free) {
    WAAM_THROW_UNLESS(f.name != "clamps" || !model.clamp_w_m2k.empty(),
                      options.data.string() << ": --free clamps: the scenario has no thermal.clamps[] (nothing to "
                                               "scale)");
  }
  const ThermalParameters start = FitStart(model, free);
  const ReplayResiduals residuals(model, free, start, window);
  WAAM_THROW_UNLESS(residuals.size() > free.size(),
                    "--window '" << options.window << "': " << residuals.size() << " measured temperatures in it; "
                                 "the fit needs more than the " << free.size() << " free parameters");
  std::string grid_note;
  const std::unique_ptr<const JacobianGrid> jacobian_grid =
      MakeJacobianGrid(options, model, free, start, window, &grid_note);
  residuals.KeepRuns();  // the start values' and the fitted values' figures continue them (WholeLogAt)
  PrintLogIssues(model.log, false, out);
  out << "fit thermal: " << options.data.string() << ", window " << window.first << ".." << window.second << " s ("
      << residuals.size() << " thermocouple readings), free";
  for (const FreeParameter& f : free) out << " " << f.name;
  out << "\n" << grid_note;

  std::vector<double> x(free.size());
  for (std::size_t k = 0; k < free.size(); ++k) x[k] = start.*(free[k].member) / free[k].scale;
  std::vector<double> seed;
  const std::vector<double> x0 = x;  // before the coarse stage moves x
  const nlohmann::json coarse_doc = RunCoarseStage(options, model, residuals, free, x, seed, out);
  const StageOutcome fine =
      internal::SolveStage(residuals, x, options.max_iterations, std::move(seed), {options.prior_weight, x0},
                           IterationLog(options), jacobian_grid ? &jacobian_grid->residuals : nullptr);
  const nlohmann::json solver = internal::StageSolverJson(fine);
  const int iterations = solver["iterations"].get<int>();

  const ThermalParameters fitted = residuals.Parameters(fine.x.data());
  const bool converged = fine.usable && fine.termination == "CONVERGENCE";
  std::string message = fine.message;
  if (!fine.error.empty()) message = fine.error;
  if (!converged) message = fine.termination + " after " + std::to_string(iterations) + " iterations: " + message;
  // The whole log with the start and the fitted values (the window's fit and the held-out prediction): the fit's own
  // replays at those values continued where they were kept, else fresh ones; either is what `waam thermal replay
  // --parameters fitted.json` gives (a replay of the window runs on until the solver's batches hold its end).
  const ReplaySimulation start_run = residuals.WholeLogAt(start);
  const ReplaySimulation fitted_run = converged ? residuals.WholeLogAt(fitted) : start_run;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  nlohmann::json doc = ThermalFitDoc(model, free, start, fitted, start_run, fitted_run, window, solver);
  doc["coarse"] = coarse_doc;
  doc["jacobian_cell_mm"] =
      jacobian_grid ? nlohmann::json(jacobian_grid->model.settings.cell_mm) : nlohmann::json(nullptr);
  doc["identifiability"] = IdentifiabilityJson(residuals, fitted, fine, options.prior_weight);
  if (!doc["identifiability"].is_null()) {
    // The grid its Jacobian was differenced on at the answer (null: none was made there).
    doc["identifiability"]["jacobian_cell_mm"] =
        fine.differenced_at_x ? nlohmann::json(model.settings.cell_mm)
        : fine.coarse_at_x    ? nlohmann::json(jacobian_grid->model.settings.cell_mm)
                              : nlohmann::json(nullptr);
  }
  doc["prior"] = options.prior_weight > 0.0
                     ? nlohmann::json{{"weight_c", options.prior_weight}, {"toward", ThermalValuesJson(free, start)}}
                     : nlohmann::json(nullptr);
  doc["time_s"] = seconds;
  doc["cpu_s"] = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  doc["scenario"] = options.data.string();
  doc["log"] = {{"file", model.log.file}, {"rows", model.log.time_s.size()}, {"duration_s", model.log.time_s.back()}};
  doc["log_issues"] = LogIssuesJson(model.log);
  PrintThermalFit(free, start, fitted, doc, iterations, fine.replays, seconds, out);
  internal::PrintIdentifiability(doc["identifiability"], model.settings.cell_mm, out);
  return internal::Finish(converged, message, doc, options, out);
}

}  // namespace waam::analysis
