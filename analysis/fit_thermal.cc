// `waam fit thermal`: Ceres moves the free thermal parameters until the replayed thermocouples match the measured
// ones inside a window of the log; the rest of the log is predicted (held out).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>

#include <ceres/ceres.h>

#include "analysis/fit_command.h"
#include "analysis/fit_internal.h"
#include "analysis/replay_command.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"

namespace waam::analysis {

namespace {

// A free parameter: its name on the command line, its member, the scale Ceres sees it in and its bounds.
struct FreeParameter {
  std::string name;
  double ThermalParameters::*member;
  double scale;       // x = value / scale, so every x is of order 1
  double lo, hi;      // bounds of the value
  std::string set;    // the scenario key it belongs to (--set)
};

const std::vector<FreeParameter>& AllFree() {
  static const std::vector<FreeParameter> all = {
      {"efficiency", &ThermalParameters::efficiency, 1.0, 0.2, 1.0, "process.arc.efficiency"},
      {"convection", &ThermalParameters::convection_w_m2k, 10.0, 0.0, 500.0, "thermal.convection_w_m2k"},
      {"contact", &ThermalParameters::table_conductance_w_m2k, 100.0, 0.0, 1.0e5, "thermal.table.conductance_w_m2k"},
      {"emissivity", &ThermalParameters::emissivity, 1.0, 0.02, 1.0, "thermal.emissivity"},
  };
  return all;
}

// `--set` lines that make a scenario use `p` (emissivity only when set).
nlohmann::json SetLines(const ThermalParameters& p) {
  nlohmann::json lines = nlohmann::json::array();
  for (const FreeParameter& f : AllFree()) {
    const double v = p.*(f.member);
    if (f.name == "emissivity" && v < 0.0) continue;
    std::ostringstream s;
    s << f.set << "=" << std::setprecision(8) << v;
    lines.push_back(s.str());
  }
  return lines;
}

std::vector<FreeParameter> ResolveFree(const std::vector<std::string>& names) {
  WAAM_THROW_UNLESS(!names.empty(), "--free: name at least one of efficiency, convection, contact, emissivity");
  std::vector<FreeParameter> free;
  for (const std::string& name : names) {
    const auto it = std::find_if(AllFree().begin(), AllFree().end(), [&](const auto& f) { return f.name == name; });
    WAAM_THROW_UNLESS(it != AllFree().end(), "--free '" << name << "': must be efficiency, convection, contact or "
                                                            "emissivity");
    for (const FreeParameter& f : free) WAAM_THROW_UNLESS(f.name != name, "--free '" << name << "': given twice");
    free.push_back(*it);
  }
  return free;
}

// The residuals of one replay to the window's end: simulated - measured at every compared row, degC.
class ReplayResiduals {
 public:
  ReplayResiduals(const ReplayModel& model, const std::vector<FreeParameter>& free, const ThermalParameters& start,
                  std::pair<double, double> window)
      : model_(model), free_(free), start_(start), window_(window) {
    // The rows compared: measured in the window (a probe not yet in metal at the start gives 0 there later too).
    for (std::size_t p = 0; p < model.probes.size(); ++p) {
      for (std::size_t i = 0; i < model.log.time_s.size(); ++i) {
        const double t = model.log.time_s[i];
        if (t >= window.first && t <= window.second && std::isfinite(model.log.probe_c[p][i])) used_.push_back({p, i});
      }
    }
  }
  std::size_t size() const { return used_.size(); }
  const FreeParameter& free(std::size_t k) const { return free_[k]; }

  ThermalParameters Parameters(const double* x) const {
    ThermalParameters p = start_;
    for (std::size_t k = 0; k < free_.size(); ++k) {
      p.*(free_[k].member) = std::clamp(x[k] * free_[k].scale, free_[k].lo, free_[k].hi);
    }
    return p;
  }

  // One replay; false when the model refuses the parameters.
  bool Run(const double* x, double* residuals) const {
    const ReplaySimulation sim = SimulateReplay(model_, Parameters(x), window_.second);
    ++replays_;
    for (std::size_t r = 0; r < used_.size(); ++r) {
      const auto [p, i] = used_[r];
      const double s = sim.probe_c[p][i];
      residuals[r] = std::isfinite(s) ? s - model_.log.probe_c[p][i] : 0.0;
    }
    return true;
  }
  int replays() const { return replays_.load(); }

 private:
  const ReplayModel& model_;
  std::vector<FreeParameter> free_;
  ThermalParameters start_;
  std::pair<double, double> window_;
  std::vector<std::pair<std::size_t, std::size_t>> used_;
  mutable std::atomic<int> replays_{0};
};

// Forward differences over whole replays, the base replay and the n perturbed ones run in parallel (each its own
// ThermalSimulation). The step is 1 % of each parameter's scale: the solver's CG tolerance (0.01 K) makes the
// temperatures noisy at the 1e-3 K level, so Ceres' default relative step (1e-6) would difference noise. The last
// point's residuals are kept, so a Jacobian asked at the point whose cost Ceres just evaluated costs n replays.
class ReplayCost : public ceres::CostFunction {
 public:
  explicit ReplayCost(const ReplayResiduals& residuals, int n) : residuals_(residuals), n_(n) {
    mutable_parameter_block_sizes()->push_back(n);
    set_num_residuals(static_cast<int>(residuals.size()));
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* x = parameters[0];
    const std::size_t m = residuals_.size();
    const bool cached = !cache_x_.empty() && std::equal(cache_x_.begin(), cache_x_.end(), x);
    const bool jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    if (cached && !jacobian) {
      std::copy(cache_r_.begin(), cache_r_.end(), residuals);
      return true;
    }
    // Run 0 is the point itself (unless cached), run k + 1 the point with x_k moved by its step.
    const std::size_t runs = jacobian ? n_ + 1 : 1;
    std::vector<std::vector<double>> out(runs, std::vector<double>(m));
    std::vector<double> step(n_, 0.0);
    for (int k = 0; k < n_; ++k) {
      const FreeParameter& f = residuals_.free(k);
      step[k] = (x[k] + 0.01) * f.scale > f.hi ? -0.01 : 0.01;  // backward at the upper bound
    }
    try {
      ParallelFor(runs, [&](std::size_t run) {
        if (run == 0 && cached) return;
        std::vector<double> xs(x, x + n_);
        if (run > 0) xs[run - 1] += step[run - 1];
        residuals_.Run(xs.data(), out[run].data());
      });
    } catch (const std::exception& e) {  // an exception must not cross Ceres
      error_ = e.what();
      return false;
    }
    if (cached) out[0] = cache_r_;
    cache_x_.assign(x, x + n_);
    cache_r_ = out[0];
    std::copy(out[0].begin(), out[0].end(), residuals);
    if (jacobian) {
      for (std::size_t r = 0; r < m; ++r) {
        for (int k = 0; k < n_; ++k) jacobians[0][r * n_ + k] = (out[k + 1][r] - out[0][r]) / step[k];
      }
    }
    return true;
  }
  const std::string& error() const { return error_; }

 private:
  const ReplayResiduals& residuals_;
  int n_;
  mutable std::vector<double> cache_x_, cache_r_;
  mutable std::string error_;
};

class ThermalFitStop : public ceres::IterationCallback {
 public:
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return InterruptRequested() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }
};

nlohmann::json ThermalValuesJson(const std::vector<FreeParameter>& free, const ThermalParameters& p) {
  nlohmann::json j = nlohmann::json::object();
  for (const FreeParameter& f : free) j[f.name] = p.*(f.member);
  return j;
}

}  // namespace

FitOutcome internal::RunFitThermal(const FitOptions& options, std::ostream& out) {
  const auto clock_start = std::chrono::steady_clock::now();
  const std::vector<FreeParameter> free = ResolveFree(options.free);
  WAAM_THROW_UNLESS(options.max_iterations >= 1 && options.max_iterations <= 1000,
                    "--max-iter = " << options.max_iterations << ": must be in [1, 1000]");
  WAAM_THROW_UNLESS(!options.window.empty(), "--window START:END is required: the part of the log fitted, in s");
  const ReplayModel model = LoadReplayModel(options.data, options.overrides, options.start);
  const std::pair<double, double> window = ParseLogWindow(options.window, model.log, "--window");
  ThermalParameters start = model.parameters;
  // A free emissivity starts from the deposit's own (the scenario's < 0 means "each material's").
  if (start.emissivity < 0.0) {
    for (const FreeParameter& f : free) {
      if (f.name == "emissivity") start.emissivity = model.settings.deposit.emissivity;
    }
  }
  const ReplayResiduals residuals(model, free, start, window);
  WAAM_THROW_UNLESS(residuals.size() > free.size(),
                    "--window '" << options.window << "': " << residuals.size() << " measured temperatures in it; "
                                 "the fit needs more than the " << free.size() << " free parameters");
  PrintLogIssues(model.log, false, out);
  out << "fit thermal: " << options.data.string() << ", window " << window.first << ".." << window.second << " s ("
      << residuals.size() << " thermocouple readings), free";
  for (const FreeParameter& f : free) out << " " << f.name;
  out << "\n";

  std::vector<double> x(free.size());
  for (std::size_t k = 0; k < free.size(); ++k) x[k] = start.*(free[k].member) / free[k].scale;
  auto* cost = new ReplayCost(residuals, static_cast<int>(free.size()));
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, x.data());
  for (std::size_t k = 0; k < free.size(); ++k) {
    problem.SetParameterLowerBound(x.data(), static_cast<int>(k), free[k].lo / free[k].scale);
    problem.SetParameterUpperBound(x.data(), static_cast<int>(k), free[k].hi / free[k].scale);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  // Ceres asks the Jacobian with every new point (n + 1 replays each), so the tolerances end the fit once the cost
  // changes by less than 0.1 % or the scaled parameters by less than 0.1 %: far below the thermocouples' noise.
  solver.function_tolerance = 1e-3;
  solver.parameter_tolerance = 1e-3;
  solver.gradient_tolerance = 1e-8;
  solver.logging_type = ceres::SILENT;
  solver.num_threads = 1;  // the parallelism is inside the cost (replays side by side)
  ThermalFitStop stop;
  solver.callbacks.push_back(&stop);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  CheckInterrupt();

  const ThermalParameters fitted = residuals.Parameters(x.data());
  const models::SolverTermination termination =
      models::TerminationNamed(ceres::TerminationTypeToString(summary.termination_type));
  const bool converged = summary.IsSolutionUsable() && termination == models::SolverTermination::kConvergence;
  std::string message = summary.message;
  if (!cost->error().empty()) message = cost->error();
  if (!converged) {
    message = std::string(NameOf(termination)) + " after " +
              std::to_string(summary.iterations.size()) + " iterations: " + message;
  }
  // The whole log replayed with the fitted values: the window's fit and the held-out prediction.
  const ReplaySimulation start_run = SimulateReplay(model, start);
  const ReplaySimulation fitted_run = converged ? SimulateReplay(model, fitted) : start_run;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  nlohmann::json doc;
  doc["parameters"] = ThermalParametersJson(fitted);
  doc["set"] = SetLines(fitted);
  doc["free"] = nlohmann::json::array();
  for (const FreeParameter& f : free) doc["free"].push_back(f.name);
  // A value that ended on its bound is a fit the bounds decided, not the data: listed, and said on stdout.
  doc["at_bound"] = nlohmann::json::array();
  for (const FreeParameter& f : free) {
    const double v = fitted.*(f.member);
    if (v <= f.lo + 1e-9 * f.scale || v >= f.hi - 1e-9 * f.scale) doc["at_bound"].push_back(f.name);
  }
  doc["start"] = ThermalValuesJson(free, start);
  doc["fitted"] = ThermalValuesJson(free, fitted);
  doc["window"] = ReplayErrorsJson(model, fitted_run, window.first, window.second);
  doc["held_out"] = ReplayErrorsJson(model, fitted_run, window.first, window.second, true);
  doc["start_window"] = ReplayErrorsJson(model, start_run, window.first, window.second)["overall"];
  doc["start_held_out"] = ReplayErrorsJson(model, start_run, window.first, window.second, true)["overall"];
  doc["solver"] = {{"termination", termination},
                   {"message", summary.message},
                   {"iterations", summary.iterations.size()},
                   {"initial_cost", summary.initial_cost},
                   {"final_cost", summary.final_cost},
                   {"replays", residuals.replays()},
                   {"report", summary.BriefReport()}};
  doc["time_s"] = seconds;
  doc["scenario"] = options.data.string();
  doc["log"] = {{"file", model.log.file}, {"rows", model.log.time_s.size()}, {"duration_s", model.log.time_s.back()}};
  doc["log_issues"] = LogIssuesJson(model.log);

  out << std::setprecision(5);
  for (const FreeParameter& f : free) {
    out << "  " << std::left << std::setw(11) << f.name << std::right << " start " << start.*(f.member)
        << "  fitted " << fitted.*(f.member) << "\n";
  }
  for (const auto& name : doc["at_bound"]) {
    out << "  note: " << name.get<std::string>() << " ended on its bound: the data would move it further\n";
  }
  auto rmse = [](const nlohmann::json& j) { return j["overall"]["rmse_c"].dump(); };
  out << "  window   rmse " << rmse(doc["window"]) << " degC (start " << doc["start_window"]["rmse_c"].dump()
      << ")\n  held out rmse " << rmse(doc["held_out"]) << " degC (start " << doc["start_held_out"]["rmse_c"].dump()
      << ")\n  solver   Ceres " << doc["solver"]["termination"].get<std::string>() << ", " << summary.iterations.size()
      << " iterations, " << residuals.replays() << " replays, " << seconds << " s\n";
  return internal::Finish(converged, message, doc, options, out);
}

}  // namespace waam::analysis
