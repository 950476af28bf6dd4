// `waam fit thermal`: Ceres moves the free thermal parameters until the replayed thermocouples match the measured
// ones inside a window of the log; the rest of the log is predicted (held out).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <iomanip>
#include <memory>
#include <mutex>
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

// A free parameter: its name on the command line, its member, its scale and its bounds.
struct FreeParameter {
  std::string name;
  double ThermalParameters::*member;
  double scale;       // x = value / scale, so every x is of order 1
  double lo, hi;      // bounds of the value (hi = +inf: a lower bound only)
  std::string set;    // the scenario key it belongs to (--set)
  // Ceres' variable u for this parameter: x = map.ToScaled(u) (logistic between two bounds, exp above one).
  internal::ParameterMap map() const { return {lo / scale, hi / scale}; }
};

constexpr double kNoBound = std::numeric_limits<double>::infinity();
// The largest change of Ceres' variable u per step (a factor e^2 = 7.4 in x - lo above a lower bound).
constexpr double kMaxFreeStep = 2.0;

const std::vector<FreeParameter>& AllFree() {
  static const std::vector<FreeParameter> all = {
      {"efficiency", &ThermalParameters::efficiency, 1.0, 0.2, 1.0, "process.arc.efficiency"},
      {"convection", &ThermalParameters::convection_w_m2k, 10.0, 0.0, kNoBound, "thermal.convection_w_m2k"},
      {"contact", &ThermalParameters::table_conductance_w_m2k, 100.0, 0.0, kNoBound,
       "thermal.table.conductance_w_m2k"},
      {"emissivity", &ThermalParameters::emissivity, 1.0, 0.02, 1.0, "thermal.emissivity"},
  };
  return all;
}

// Scaled values x of Ceres' variables u, and back.
std::vector<double> ToScaled(const std::vector<FreeParameter>& free, const double* u) {
  std::vector<double> x(free.size());
  for (std::size_t k = 0; k < free.size(); ++k) x[k] = free[k].map().ToScaled(u[k]);
  return x;
}
std::vector<double> ToFree(const std::vector<FreeParameter>& free, const std::vector<double>& x) {
  std::vector<double> u(free.size());
  for (std::size_t k = 0; k < free.size(); ++k) u[k] = free[k].map().ToFree(x[k]);
  return u;
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

// The residuals of one replay to the window's end: simulated - measured at every compared row, degC. The replay of
// the best point so far (lowest cost) may be kept, so the held-out rows continue it from the window's end.
class ReplayResiduals {
 public:
  ReplayResiduals(const ReplayModel& model, const std::vector<FreeParameter>& free, const ThermalParameters& start,
                  std::pair<double, double> window)
      : model_(&model), free_(free), start_(start), window_(window) {
    // The rows compared: measured in the window (a probe not yet in metal at the start gives 0 there later too).
    for (std::size_t p = 0; p < model.probes.size(); ++p) {
      for (std::size_t i = 0; i < model.log.time_s.size(); ++i) {
        const double t = model.log.time_s[i];
        if (t >= window.first && t <= window.second && std::isfinite(model.log.probe_c[p][i])) used_.push_back({p, i});
      }
    }
  }
  std::size_t size() const { return used_.size(); }
  std::size_t free_count() const { return free_.size(); }
  const FreeParameter& free(std::size_t k) const { return free_[k]; }
  const std::vector<FreeParameter>& free() const { return free_; }
  const ReplayModel& model() const { return *model_; }
  // The same rows on another grid of the same log (a coarse stage).
  ReplayResiduals OnModel(const ReplayModel& model) const {
    return ReplayResiduals(model, free_, start_, window_);
  }

  // The parameters at scaled values `x` (within the bounds).
  ThermalParameters Parameters(const double* x) const {
    ThermalParameters p = start_;
    for (std::size_t k = 0; k < free_.size(); ++k) {
      p.*(free_[k].member) = x[k] * free_[k].scale;
      WAAM_DEMAND(p.*(free_[k].member) >= free_[k].lo && p.*(free_[k].member) <= free_[k].hi);
    }
    return p;
  }

  // One replay to the window's end at scaled values `x`; `keep`: keep the replay when its cost is the lowest so far.
  // Returns how many compared rows the replay has no temperature at (NaN: no metal at the probe yet, which the log
  // alone decides; a replay that blows up has more).
  std::size_t Run(const double* x, double* residuals, bool keep) const {
    auto run = std::make_unique<ReplayRun>(*model_, Parameters(x));
    run->AdvanceTo(window_.second);
    const ReplaySimulation sim = run->Result();
    ++replays_;
    double cost = 0.0;
    std::size_t missing = 0;
    for (std::size_t r = 0; r < used_.size(); ++r) {
      const auto [p, i] = used_[r];
      const double s = sim.probe_c[p][i];
      residuals[r] = std::isfinite(s) ? s - model_->log.probe_c[p][i] : 0.0;
      missing += std::isfinite(s) ? 0 : 1;
      cost += residuals[r] * residuals[r];
    }
    if (!keep) return missing;
    const std::lock_guard<std::mutex> lock(kept_mutex_);
    if (kept_ == nullptr || cost < kept_cost_) {
      kept_ = std::move(run);
      kept_cost_ = cost;
    }
    return missing;
  }
  // The kept replay if it was made with the parameters of `x`, else null.
  std::unique_ptr<ReplayRun> TakeKept(const double* x) const {
    const ThermalParameters p = Parameters(x);
    if (kept_ == nullptr) return nullptr;
    const ThermalParameters& q = kept_->parameters();
    const bool same = p.efficiency == q.efficiency && p.convection_w_m2k == q.convection_w_m2k &&
                      p.table_conductance_w_m2k == q.table_conductance_w_m2k && p.emissivity == q.emissivity;
    return same ? std::move(kept_) : nullptr;
  }
  int replays() const { return replays_.load(); }

 private:
  const ReplayModel* model_;
  std::vector<FreeParameter> free_;
  ThermalParameters start_;
  std::pair<double, double> window_;
  std::vector<std::pair<std::size_t, std::size_t>> used_;
  mutable std::atomic<int> replays_{0};
  mutable std::mutex kept_mutex_;
  mutable std::unique_ptr<ReplayRun> kept_;
  mutable double kept_cost_ = 0.0;
};

// The residuals at Ceres' variables u (x = map(u)). The Jacobian is differenced in the scaled values x, forward
// differences over whole replays, the base replay and the n perturbed ones run in parallel (each its own
// ThermalSimulation), and handed to Ceres by the chain rule, d r/d u_k = d r/d x_k dx_k/du_k. The step is 1 % of
// each parameter's scale in x (not in u, whose step would shrink with x - lo toward the solver's noise near a lower
// bound): the solver's CG tolerance (0.01 K) makes the temperatures noisy at the 1e-3 K level, so Ceres' default
// relative step (1e-6) would difference noise. The last point's residuals are kept, so a Jacobian asked at the point
// whose cost Ceres just evaluated costs n replays. A `seed` Jacobian in x (the coarse stage's, m x n row-major)
// stands in for the differences at the first point only.
// A replay with more rows without a temperature than the first one (blown up) is refused: Ceres counts the point as
// an unsuccessful step and shrinks its trust region.
class ReplayCost : public ceres::CostFunction {
 public:
  ReplayCost(const ReplayResiduals& residuals, bool keep, std::vector<double> seed = {})
      : residuals_(residuals), n_(static_cast<int>(residuals.free_count())), keep_(keep), seed_(std::move(seed)) {
    mutable_parameter_block_sizes()->push_back(n_);
    set_num_residuals(static_cast<int>(residuals.size()));
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* u = parameters[0];
    const std::vector<double> xv = ToScaled(residuals_.free(), u);
    if (!std::all_of(xv.begin(), xv.end(), [](double v) { return std::isfinite(v); })) return false;  // exp overflow
    const double* x = xv.data();
    const std::size_t m = residuals_.size();
    const bool cached = !cache_x_.empty() && std::equal(cache_x_.begin(), cache_x_.end(), x);
    const bool jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    const bool seeded = jacobian && !seed_.empty() && (cache_x_.empty() || cached) && !seed_used_;
    // Ceres (2.1) asks the Jacobian with the candidate point and again once it accepts it: the second is the first.
    if (cached && (!jacobian || differenced_)) {
      if (residuals != nullptr) std::copy(cache_r_.begin(), cache_r_.end(), residuals);
      if (jacobian) ChainRule(u, jacobians[0]);
      return true;
    }
    // Run 0 is the point itself (unless cached), run k + 1 the point with x_k moved by its step.
    const std::size_t runs = jacobian && !seeded ? n_ + 1 : 1;
    std::vector<std::vector<double>> out(runs, std::vector<double>(m));
    std::vector<double> step(n_, 0.0);
    for (int k = 0; k < n_; ++k) {
      const FreeParameter& f = residuals_.free(k);
      step[k] = (x[k] + 0.01) * f.scale > f.hi ? -0.01 : 0.01;  // backward at the upper bound
    }
    std::vector<std::size_t> missing(runs, 0);
    try {
      ParallelFor(runs, [&](std::size_t run) {
        if (run == 0 && cached) return;
        std::vector<double> xs(x, x + n_);
        if (run > 0) xs[run - 1] += step[run - 1];
        missing[run] = residuals_.Run(xs.data(), out[run].data(), keep_ && run == 0);
      });
    } catch (const std::exception& e) {  // an exception must not cross Ceres
      error_ = e.what();
      return false;
    }
    if (first_missing_ < 0) first_missing_ = static_cast<long>(missing[0]);
    for (std::size_t run = cached ? 1 : 0; run < runs; ++run) {
      if (static_cast<long>(missing[run]) > first_missing_) return false;
    }
    if (cached) out[0] = cache_r_;
    cache_x_.assign(x, x + n_);
    cache_r_ = out[0];
    differenced_ = jacobian && !seeded;
    if (residuals != nullptr) std::copy(out[0].begin(), out[0].end(), residuals);
    if (jacobian) {
      if (seeded) {
        seed_used_ = true;
        last_jacobian_ = seed_;
      } else {
        last_jacobian_.assign(m * n_, 0.0);
        for (std::size_t r = 0; r < m; ++r) {
          for (int k = 0; k < n_; ++k) last_jacobian_[r * n_ + k] = (out[k + 1][r] - out[0][r]) / step[k];
        }
      }
      ChainRule(u, jacobians[0]);
      jacobians_.emplace_back(cache_x_, last_jacobian_);
    }
    return true;
  }
  const std::string& error() const { return error_; }
  // The Jacobian in x at scaled values `x` (the last one when none was made there: a seeded first point).
  const std::vector<double>& JacobianAt(const std::vector<double>& x) const {
    for (const auto& [at, jacobian] : jacobians_) {
      if (at == x) return jacobian;
    }
    return last_jacobian_;
  }
  // The last Jacobian in x, m x n row-major (the next stage's seed).
  const std::vector<double>& last_jacobian() const { return last_jacobian_; }

 private:
  // Ceres' Jacobian in u at `u` from the last one in x: column k times dx_k/du_k.
  void ChainRule(const double* u, double* out) const {
    const std::size_t m = residuals_.size();
    for (int k = 0; k < n_; ++k) {
      const double slope = residuals_.free(k).map().Slope(u[k]);
      for (std::size_t r = 0; r < m; ++r) out[r * n_ + k] = last_jacobian_[r * n_ + k] * slope;
    }
  }

  const ReplayResiduals& residuals_;
  int n_;
  bool keep_;
  std::vector<double> seed_;
  mutable bool seed_used_ = false;
  mutable bool differenced_ = false;  // last_jacobian_ was differenced at cache_x_
  mutable long first_missing_ = -1;       // rows without a temperature in the first replay
  mutable std::vector<double> cache_x_, cache_r_, last_jacobian_;
  mutable std::vector<std::pair<std::vector<double>, std::vector<double>>> jacobians_;  // every point's (x, J)
  mutable std::string error_;
};

// The weak prior (--prior W): residual k = W (x_k - x0_k), degC, x the scaled parameters (physical units, whatever
// Ceres' variable u is), x0 the start's. A change of one scale unit costs as much as one reading W degC off; with
// thermocouple noise sigma it is a Gaussian prior of standard deviation sigma / W scale units. Its Jacobian in u is
// W dx_k/du_k.
class PriorCost : public ceres::CostFunction {
 public:
  PriorCost(std::vector<FreeParameter> free, std::vector<double> x0, double weight)
      : free_(std::move(free)), x0_(std::move(x0)), weight_(weight) {
    mutable_parameter_block_sizes()->push_back(static_cast<int>(x0_.size()));
    set_num_residuals(static_cast<int>(x0_.size()));
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const std::size_t n = x0_.size();
    const std::vector<double> x = ToScaled(free_, parameters[0]);
    for (std::size_t k = 0; k < n; ++k) residuals[k] = weight_ * (x[k] - x0_[k]);
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      std::fill(jacobians[0], jacobians[0] + n * n, 0.0);
      for (std::size_t k = 0; k < n; ++k) jacobians[0][k * n + k] = weight_ * free_[k].map().Slope(parameters[0][k]);
    }
    return true;
  }
  // 1/2 sum of the residuals squared at `x`.
  double Cost(const std::vector<double>& x) const {
    double c = 0.0;
    for (std::size_t k = 0; k < x0_.size(); ++k) c += 0.5 * std::pow(weight_ * (x[k] - x0_[k]), 2);
    return c;
  }

 private:
  std::vector<FreeParameter> free_;
  std::vector<double> x0_;
  double weight_;
};

// Ceres' steps in u, each coordinate capped at +-kMaxFreeStep (Plus; its Jacobian at delta = 0 is the identity). Near
// a lower bound dx/du is small, so the linearisation in u asks steps of hundreds of units (a factor e^100 in x) that
// the trust region, scaled by the Jacobian's columns, does not hold back: the cap takes the step part of the way, and
// the next Jacobian, from a point where dx/du is larger, goes on. The values themselves are never clamped.
class CappedStep : public ceres::Manifold {
 public:
  explicit CappedStep(int n) : n_(n) {}
  int AmbientSize() const override { return n_; }
  int TangentSize() const override { return n_; }
  bool Plus(const double* u, const double* delta, double* out) const override {
    for (int k = 0; k < n_; ++k) out[k] = u[k] + std::clamp(delta[k], -kMaxFreeStep, kMaxFreeStep);
    return true;
  }
  bool PlusJacobian(const double*, double* jacobian) const override { return Identity(jacobian); }
  bool Minus(const double* y, const double* u, double* delta) const override {
    for (int k = 0; k < n_; ++k) delta[k] = y[k] - u[k];
    return true;
  }
  bool MinusJacobian(const double*, double* jacobian) const override { return Identity(jacobian); }

 private:
  bool Identity(double* jacobian) const {
    std::fill(jacobian, jacobian + n_ * n_, 0.0);
    for (int k = 0; k < n_; ++k) jacobian[k * n_ + k] = 1.0;
    return true;
  }
  int n_;
};

class ThermalFitStop : public ceres::IterationCallback {
 public:
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return InterruptRequested() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }
};

// One stage of the fit: Ceres on one grid, from `x` (scaled values).
struct StageOutcome {
  std::vector<double> x;          // the answer, scaled values
  ceres::Solver::Summary summary;
  std::string error;              // why a replay failed (empty: none did)
  std::vector<double> jacobian;   // the last one Ceres used, in x, m x n row-major
  std::vector<double> jacobian_at_x;  // the one at the stage's answer x, in x
  double data_cost = 0.0;         // the final cost without the prior's part
  int replays = 0;
  double seconds = 0.0;           // wall
};

// `prior`: the weak prior's weight (0: none) and x0, the start's scaled values it pulls toward.
StageOutcome SolveStage(const ReplayResiduals& residuals, const std::vector<double>& x_start, int max_iterations,
                        bool keep, std::vector<double> seed, std::pair<double, std::vector<double>> prior) {
  const auto clock_start = std::chrono::steady_clock::now();
  StageOutcome outcome;
  // Ceres runs unbounded on u; the bounds are kept by the maps x(u) (ParameterMap): on a bounded problem Ceres 2.1
  // evaluates every trust-region candidate through a projected line search that asks the gradient, i.e. a
  // differenced Jacobian (n + 1 replays) at each point it tries instead of one replay.
  std::vector<double> u = ToFree(residuals.free(), x_start);
  auto* cost = new ReplayCost(residuals, keep, std::move(seed));
  ceres::Problem problem;  // owns `cost` and `prior_cost`
  problem.AddResidualBlock(cost, nullptr, u.data());
  PriorCost* prior_cost =
      prior.first > 0.0 ? new PriorCost(residuals.free(), prior.second, prior.first) : nullptr;
  if (prior_cost != nullptr) problem.AddResidualBlock(prior_cost, nullptr, u.data());
  problem.SetManifold(u.data(), new CappedStep(static_cast<int>(u.size())));  // owned by `problem`
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = max_iterations;
  // Ceres asks the Jacobian with every new point (n + 1 replays each), so the tolerances end the fit once the cost
  // changes by less than 0.1 % or the scaled parameters by less than 0.1 %: far below the thermocouples' noise.
  solver.function_tolerance = 1e-3;
  solver.parameter_tolerance = 1e-3;
  solver.gradient_tolerance = 1e-8;
  solver.logging_type = ceres::SILENT;
  solver.num_threads = 1;  // the parallelism is inside the cost (replays side by side)
  ThermalFitStop stop;
  solver.callbacks.push_back(&stop);
  ceres::Solve(solver, &problem, &outcome.summary);
  CheckInterrupt();
  const std::vector<double> x = ToScaled(residuals.free(), u.data());
  outcome.error = cost->error();
  outcome.jacobian = cost->last_jacobian();
  outcome.jacobian_at_x = cost->JacobianAt(x);
  outcome.data_cost = outcome.summary.final_cost - (prior_cost != nullptr ? prior_cost->Cost(x) : 0.0);
  outcome.x = x;
  outcome.replays = residuals.replays();
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return outcome;
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
  std::vector<std::string> overrides = options.overrides;
  std::ostringstream cell;
  cell << "thermal.cell_mm=" << std::setprecision(17) << coarse_mm;
  overrides.push_back(cell.str());
  const ReplayModel coarse_model = LoadReplayModel(options.data, overrides, options.start);
  const ReplayResiduals coarse = residuals.OnModel(coarse_model);
  std::vector<double> x0 = x;
  const StageOutcome stage = SolveStage(coarse, x, options.max_iterations, false, {}, {options.prior_weight, x0});
  const bool usable = stage.summary.IsSolutionUsable() && stage.error.empty();
  if (usable) x = stage.x, seed = stage.jacobian;
  const ThermalParameters reached = coarse.Parameters(stage.x.data());
  out << "  coarse " << coarse_mm << " mm:" << std::setprecision(5);
  for (const FreeParameter& f : free) out << " " << f.name << " " << reached.*(f.member);
  out << " (" << stage.summary.iterations.size() << " iterations, " << stage.replays << " replays, "
      << stage.seconds << " s" << (usable ? "" : "; not used: " + stage.summary.message + stage.error) << ")\n";
  return {{"cell_mm", coarse_mm},
          {"fitted", ThermalValuesJson(free, reached)},
          {"used", usable},
          {"termination", ceres::TerminationTypeToString(stage.summary.termination_type)},
          {"iterations", stage.summary.iterations.size()},
          {"replays", stage.replays},
          {"time_s", stage.seconds}};
}

// The fit's record without its timings: the values, those that ended on a bound, the errors of the fitted and the
// start runs over the window and the held-out rest of the log, and the solver's summary.
nlohmann::json ThermalFitDoc(const ReplayModel& model, const std::vector<FreeParameter>& free,
                             const ThermalParameters& start, const ThermalParameters& fitted,
                             const ReplaySimulation& start_run, const ReplaySimulation& fitted_run,
                             const std::pair<double, double>& window, const ceres::Solver::Summary& summary,
                             models::SolverTermination termination, int replays) {
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
  doc["solver"] = {{"termination", termination},
                   {"message", summary.message},
                   {"iterations", summary.iterations.size()},
                   {"initial_cost", summary.initial_cost},
                   {"final_cost", summary.final_cost},
                   {"replays", replays},
                   {"successful_steps", summary.num_successful_steps},
                   {"unsuccessful_steps", summary.num_unsuccessful_steps},
                   {"residual_evaluations", summary.num_residual_evaluations},
                   {"jacobian_evaluations", summary.num_jacobian_evaluations},
                   {"report", summary.BriefReport()}};
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
      << " iterations, " << replays << " replays, " << seconds << " s\n";
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

// The standard deviations, the strong correlations (|r| > 0.9), the weakest combination and what is undetermined.
void PrintIdentifiability(const nlohmann::json& id, std::ostream& out) {
  if (id.is_null()) return;
  out << std::setprecision(3) << "  1 sd      ";
  for (const auto& [name, sd] : id["standard_deviation"].items()) out << " " << name << " " << sd.get<double>();
  if (id["noise_c"].is_number()) out << " (noise " << id["noise_c"].get<double>() << " degC)";
  out << "\n";
  for (const auto& [a, row] : id["correlation"].items()) {
    for (const auto& [b, r] : row.items()) {
      if (a < b && std::abs(r.get<double>()) > 0.9) {
        out << "  correlated " << a << ", " << b << ": " << r.get<double>() << "\n";
      }
    }
  }
  if (id["condition_number"].is_number()) {
    out << "  weakest    condition " << id["condition_number"].get<double>() << ", 1 sd along:";
    for (const auto& [name, d] : id["weakest"].items()) out << " " << name << " " << std::showpos << d.get<double>();
    out << std::noshowpos << "\n";
  }
  for (const auto& name : id["undetermined"]) {
    out << "  note: the window does not determine " << name.get<std::string>() << " (1 sd over "
        << 100.0 * internal::kUndeterminedFraction << " % of its value): fix it (fewer --free) or add --prior\n";
  }
}

}  // namespace

FitOutcome internal::RunFitThermal(const FitOptions& options, std::ostream& out) {
  const auto clock_start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  const std::vector<FreeParameter> free = ResolveFree(options.free);
  WAAM_THROW_UNLESS(options.max_iterations >= 1 && options.max_iterations <= 1000,
                    "--max-iter = " << options.max_iterations << ": must be in [1, 1000]");
  WAAM_THROW_UNLESS(std::isfinite(options.prior_weight) && options.prior_weight >= 0.0,
                    "--prior = " << options.prior_weight << ": must be a weight >= 0 degC (0: no prior)");
  WAAM_THROW_UNLESS(!options.window.empty(), "--window START:END is required: the part of the log fitted, in s");
  const ReplayModel model = LoadReplayModel(options.data, options.overrides, options.start);
  const std::pair<double, double> window = ParseLogWindow(options.window, model.log, "--window");
  const ThermalParameters start = FitStart(model, free);
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
  std::vector<double> seed;
  const std::vector<double> x0 = x;  // before the coarse stage moves x
  const nlohmann::json coarse_doc = RunCoarseStage(options, model, residuals, free, x, seed, out);
  const StageOutcome fine =
      SolveStage(residuals, x, options.max_iterations, true, std::move(seed), {options.prior_weight, x0});
  const ceres::Solver::Summary& summary = fine.summary;

  const ThermalParameters fitted = residuals.Parameters(fine.x.data());
  const models::SolverTermination termination =
      models::TerminationNamed(ceres::TerminationTypeToString(summary.termination_type));
  const bool converged = summary.IsSolutionUsable() && termination == models::SolverTermination::kConvergence;
  std::string message = summary.message;
  if (!fine.error.empty()) message = fine.error;
  if (!converged) {
    message = std::string(NameOf(termination)) + " after " +
              std::to_string(summary.iterations.size()) + " iterations: " + message;
  }
  // The whole log with the fitted values (the replay of the fitted point continued from the window's end) and with
  // the start values: the window's fit and the held-out prediction.
  const ReplaySimulation start_run = SimulateReplay(model, start);
  ReplaySimulation fitted_run = start_run;
  if (converged) {
    std::unique_ptr<ReplayRun> run = residuals.TakeKept(fine.x.data());
    if (run == nullptr) run = std::make_unique<ReplayRun>(model, fitted);
    run->AdvanceTo(std::numeric_limits<double>::infinity());
    fitted_run = run->Result();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  nlohmann::json doc = ThermalFitDoc(model, free, start, fitted, start_run, fitted_run, window, summary, termination,
                                     residuals.replays());
  doc["coarse"] = coarse_doc;
  doc["identifiability"] = IdentifiabilityJson(residuals, fitted, fine, options.prior_weight);
  doc["prior"] = options.prior_weight > 0.0
                     ? nlohmann::json{{"weight_c", options.prior_weight}, {"toward", ThermalValuesJson(free, start)}}
                     : nlohmann::json(nullptr);
  doc["time_s"] = seconds;
  doc["cpu_s"] = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  doc["scenario"] = options.data.string();
  doc["log"] = {{"file", model.log.file}, {"rows", model.log.time_s.size()}, {"duration_s", model.log.time_s.back()}};
  doc["log_issues"] = LogIssuesJson(model.log);
  PrintThermalFit(free, start, fitted, doc, summary.iterations.size(), residuals.replays(), seconds, out);
  PrintIdentifiability(doc["identifiability"], out);
  return internal::Finish(converged, message, doc, options, out);
}

}  // namespace waam::analysis
