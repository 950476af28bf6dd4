// `waam fit thermal`'s cost: the replays' residuals and their Jacobian (differenced over whole replays), the weak
// prior, and one stage of the fit with Ceres (the parameters and residuals: fit_thermal_residuals.cc).
#include "analysis/fit_thermal_cost.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <ostream>

#include <Eigen/Dense>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"

namespace waam::analysis::internal {

namespace {

// How a Jacobian was made: differenced on the stage's grid, the coarse stage's seed, or differenced on the coarser
// Jacobian grid.
enum class JacobianKind { kDifferenced, kSeed, kCoarse };

// The residuals at Ceres' variables u (x = map(u)), and their Jacobian, asked by Ceres (2.1, unbounded) at the
// start and at each point it accepts. The Jacobian is differenced in the scaled values x: forward differences over
// whole replays, the n perturbed ones in parallel (each its own ThermalSimulation), n replays that follow the solver
// choices of the point's replay (the candidate's Ceres accepted: docs/THERMAL.md, "Differencing a run"), so that
// the differences see the parameters' effect and none of the solver's switches; the step is 1 % of each
// parameter's scale (not a step in u, which would shrink with x - lo toward a lower bound, where the followed
// replays' round-off and the melt pool's steep response would dominate). It is
// handed to Ceres by the chain rule, d r/d u_k = d r/d x_k dx_k/du_k. A `seed` Jacobian in x (the coarse stage's,
// m x n row-major) stands in at the first point until RequestDifference(); with a `coarse` grid, the Jacobians are
// differenced there (1 + n replays there, the perturbed ones following the choices of the one at x) until
// RequestDifference() (the residuals stay on the stage's grid: an inexact Gauss-Newton, whose fixed point lies within
// the function tolerance of the stage's grid's; docs/REPLAY.md, "Jacobians on a coarser grid"). A replay with more
// rows without a temperature than the first one (blown up) is refused: Ceres counts the point as an unsuccessful step
// and shrinks its trust region.
class ReplayCost : public ceres::CostFunction {
 public:
  ReplayCost(const ReplayResiduals& residuals, std::vector<double> seed, const ReplayResiduals* coarse)
      : residuals_(residuals), coarse_(coarse), n_(static_cast<int>(residuals.free_count())), seed_(std::move(seed)) {
    mutable_parameter_block_sizes()->push_back(n_);
    set_num_residuals(static_cast<int>(residuals.size()));
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* u = parameters[0];
    const std::vector<double> x = ToScaled(residuals_.free(), u);
    if (!std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); })) return false;  // exp overflow
    try {
      if (jacobians == nullptr || jacobians[0] == nullptr) {
        const std::vector<double>* r = ResidualsAt(x);
        if (r == nullptr) return false;
        if (residuals != nullptr) std::copy(r->begin(), r->end(), residuals);
        return true;
      }
      if (!JacobianAt(x)) return false;
    } catch (const std::exception& e) {  // an exception must not cross Ceres
      error_ = e.what();
      return false;
    }
    if (residuals != nullptr) std::copy(point_r_.begin(), point_r_.end(), residuals);
    for (int k = 0; k < n_; ++k) {
      const double slope = residuals_.free(k).map().Slope(u[k]);
      for (std::size_t r = 0; r < residuals_.size(); ++r) jacobians[0][r * n_ + k] = point_j_[r * n_ + k] * slope;
    }
    return true;
  }

  // The next Jacobian (at the accepted point, or at the last one when Ceres starts there again) is differenced.
  void RequestDifference() { refresh_ = true, fine_ = true; }
  // The Jacobian at the last accepted point is the seed or the coarse grid's (not differenced on this grid).
  bool Undifferenced() const { return have_point_ && point_kind_ != JacobianKind::kDifferenced; }
  // The Jacobian at the last accepted point is the seed.
  bool Seeded() const { return have_point_ && point_kind_ == JacobianKind::kSeed; }
  const std::string& error() const { return error_; }
  // The Jacobian in x at `x` and how it was made (the last one and no kind when none was made there).
  std::pair<const std::vector<double>*, std::optional<JacobianKind>> JacobianOf(const std::vector<double>& x) const {
    for (auto it = made_.rbegin(); it != made_.rend(); ++it) {
      if (it->x == x) return {&it->j, it->kind};
    }
    return {&point_j_, std::nullopt};
  }
  const std::vector<double>& last_jacobian() const { return point_j_; }
  int Count(JacobianKind kind) const {
    return static_cast<int>(std::count_if(made_.begin(), made_.end(), [&](const Made& m) { return m.kind == kind; }));
  }

 private:
  struct Made {
    std::vector<double> x, j;
    JacobianKind kind;
  };

  // The residuals at `x`: the last point tried or accepted, else one replay making its own solver choices, recorded
  // (Ceres' step test compares a candidate's cost with the accepted point's, which must be the same replay's; a
  // candidate following the point's choices and replayed afresh once accepted set them apart by the switches' jumps,
  // and every later step failed). Null when the replay blew up. `choices`, when given, gets the choices of the
  // replay the residuals come from.
  const std::vector<double>* ResidualsAt(const std::vector<double>& x,
                                         std::shared_ptr<const twin::SolverChoices>* choices = nullptr) const {
    if (have_point_ && x == point_x_) {
      if (choices != nullptr) *choices = point_choices_;
      return &point_r_;
    }
    if (tried_x_.empty() || x != tried_x_) {
      std::vector<double> r(residuals_.size());
      twin::SolverChoices made;
      const std::size_t missing = residuals_.Run(x.data(), r.data(), &made);
      if (first_missing_ < 0) first_missing_ = static_cast<long>(missing);
      if (static_cast<long>(missing) > first_missing_) return nullptr;
      tried_x_ = x;
      tried_r_ = std::move(r);
      tried_choices_ = std::make_shared<const twin::SolverChoices>(std::move(made));
    }
    if (choices != nullptr) *choices = tried_choices_;
    return &tried_r_;
  }

  // Makes the Jacobian at `x` (Ceres' current point) the point's; false when a replay blew up.
  bool JacobianAt(const std::vector<double>& x) const {
    const bool same = have_point_ && x == point_x_;
    if (same && !(refresh_ && point_kind_ != JacobianKind::kDifferenced)) return true;
    std::shared_ptr<const twin::SolverChoices> choices;
    const std::vector<double>* r = ResidualsAt(x, &choices);
    if (r == nullptr) return false;
    std::vector<double> r_new = *r;
    JacobianKind kind = JacobianKind::kDifferenced;
    std::vector<double> j;
    if (!seed_.empty() && !have_point_) {
      kind = JacobianKind::kSeed, j = seed_;
    } else if (coarse_ != nullptr && !fine_) {
      kind = JacobianKind::kCoarse;
      std::vector<double> r_coarse(coarse_->size());
      twin::SolverChoices made;
      coarse_->Run(x.data(), r_coarse.data(), &made);
      if (!Difference(*coarse_, x, r_coarse, std::make_shared<const twin::SolverChoices>(std::move(made)), &j)) {
        return false;
      }
    } else if (!Difference(residuals_, x, r_new, choices, &j)) {
      return false;
    }
    point_x_ = x;
    point_r_ = std::move(r_new);
    point_choices_ = std::move(choices);
    point_j_ = j;
    point_kind_ = kind;
    have_point_ = true;
    refresh_ = false;
    made_.push_back({x, std::move(j), kind});
    return true;
  }

  // Forward differences at `x` (residuals r there, from a replay that made `choices`): the n perturbed replays in
  // parallel, each following those choices (internal numerical differentiation: docs/THERMAL.md, "Differencing a
  // run"), so that the difference sees the parameter's effect and none of the solver's switches.
  bool Difference(const ReplayResiduals& grid, const std::vector<double>& x, const std::vector<double>& r,
                  const std::shared_ptr<const twin::SolverChoices>& choices, std::vector<double>* j) const {
    const std::size_t m = grid.size();
    std::vector<std::vector<double>> out(n_, std::vector<double>(m));
    std::vector<double> step(n_);
    for (int k = 0; k < n_; ++k) {
      const FreeParameter& f = residuals_.free(k);
      step[k] = (x[k] + 0.01) * f.scale > f.hi ? -0.01 : 0.01;  // backward at the upper bound
    }
    std::vector<std::size_t> missing(n_, 0);
    ParallelFor(static_cast<std::size_t>(n_), [&](std::size_t k) {
      std::vector<double> xs = x;
      xs[k] += step[k];
      missing[k] = grid.Run(xs.data(), out[k].data(), nullptr, choices);
    });
    for (int k = 0; k < n_; ++k) {
      if (&grid == &residuals_ && static_cast<long>(missing[k]) > first_missing_) return false;
    }
    j->assign(m * n_, 0.0);
    for (std::size_t row = 0; row < m; ++row) {
      for (int k = 0; k < n_; ++k) (*j)[row * n_ + k] = (out[k][row] - r[row]) / step[k];
    }
    return true;
  }

  const ReplayResiduals& residuals_;
  const ReplayResiduals* coarse_;  // the Jacobian grid (null: none)
  int n_;
  std::vector<double> seed_;
  mutable bool refresh_ = false;  // difference the next Jacobian
  mutable bool fine_ = false;     // every later Jacobian differenced on the stage's grid
  mutable long first_missing_ = -1;         // rows without a temperature in the first replay
  mutable std::vector<double> tried_x_, tried_r_;  // the last point tried (a candidate) and its residuals
  mutable std::shared_ptr<const twin::SolverChoices> tried_choices_, point_choices_;  // their replays' choices
  mutable bool have_point_ = false;           // the point Ceres stands on (the start or the last accepted)
  mutable std::vector<double> point_x_, point_r_, point_j_;
  mutable JacobianKind point_kind_ = JacobianKind::kDifferenced;
  mutable std::vector<Made> made_;            // every Jacobian made, in order
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

// Where and since when a stage writes its line per iteration, and the iterations its earlier Ceres runs took (the
// numbers go on across runs).
struct StageLog {
  std::ostream* out = nullptr;  // null: no lines
  std::chrono::steady_clock::time_point start;
  int done = 0;
};

// A rejected step from a differenced Jacobian that promised less than this share of the point's cost ends the fit
// as converged: the candidates' costs jump by more between two replays' solver choices (on the round trip of
// docs/REPLAY.md, a step promising 0.7 % of the cost met +2.9 % to +5.2 % in three candidates), so no trust
// region can confirm such a step, and the parameters it would move lie within their standard deviations.
constexpr double kUnresolvedShare = 0.01;

// Whether the iteration's step was rejected, and the decrease of the cost its linear model predicted (Ceres'
// relative decrease is the actual decrease over it); NaN when the step was not valid.
bool Rejected(const ceres::IterationSummary& s) { return s.iteration > 0 && !s.step_is_successful; }
double PredictedDecrease(const ceres::IterationSummary& s) {
  return s.step_is_valid && s.relative_decrease != 0.0 ? s.cost_change / s.relative_decrease
                                                       : std::numeric_limits<double>::quiet_NaN();
}

// The decrease of the cost (data and prior) that the Gauss-Newton step at Ceres' point u promises, with the
// Jacobian the cost makes there (on the scenario's grid once RequestDifference() was called), the `held` coordinates
// kept: an upper bound of the decrease any of Ceres' damped steps from there promises. Also returns the cost there
// and, with `step`, the step in u (0 in the held coordinates). False when a replay failed.
bool GaussNewtonPromise(const ReplayCost& cost, const PriorCost* prior, const std::vector<double>& u,
                        const std::vector<bool>& held, double* promise, double* at,
                        std::vector<double>* step_u = nullptr) {
  const int n = static_cast<int>(u.size());
  const int m = cost.num_residuals();
  const int p = prior != nullptr ? n : 0;
  Eigen::VectorXd r(m + p);
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(m + p, n);
  std::vector<double> block(static_cast<std::size_t>(std::max(m, p)) * n);
  const double* parameters[] = {u.data()};
  double* jacobians[] = {block.data()};
  if (!cost.Evaluate(parameters, r.data(), jacobians)) return false;
  for (int row = 0; row < m; ++row) {
    for (int k = 0; k < n; ++k) j(row, k) = block[static_cast<std::size_t>(row) * n + k];
  }
  if (prior != nullptr) {
    prior->Evaluate(parameters, r.data() + m, jacobians);
    for (int row = 0; row < p; ++row) {
      for (int k = 0; k < n; ++k) j(m + row, k) = block[static_cast<std::size_t>(row) * n + k];
    }
  }
  for (int k = 0; k < n; ++k) {
    if (k < static_cast<int>(held.size()) && held[k]) j.col(k).setZero();
  }
  const Eigen::VectorXd step = j.colPivHouseholderQr().solve(-r);  // 0 in a zero column (the minimum-norm part)
  *at = 0.5 * r.squaredNorm();
  *promise = *at - 0.5 * (r + j * step).squaredNorm();
  if (step_u != nullptr) {
    step_u->assign(step.data(), step.data() + n);
    for (int k = 0; k < n; ++k) {
      if (k < static_cast<int>(held.size()) && held[k]) (*step_u)[k] = 0.0;
    }
  }
  return std::isfinite(*promise);
}

// The coordinates the Gauss-Newton step `step_u` at u pushes across a bound they lie within kStartInside of (in
// scaled units): where the linear model's minimum lies beyond the bound, Ceres on the smooth map only creeps toward
// it (a factor e^2 per step at most); the stage holds them there instead (docs/REPLAY.md, "Bounds by
// reparametrisation"). With `inward`, those it moves away from such a bound instead.
std::vector<bool> AcrossBounds(const std::vector<FreeParameter>& free, const std::vector<double>& u,
                               const std::vector<double>& step_u, bool inward) {
  std::vector<bool> across(free.size(), false);
  for (std::size_t k = 0; k < free.size(); ++k) {
    const ParameterMap map = free[k].map();
    const double x = map.ToScaled(u[k]), dx = map.Slope(u[k]) * step_u[k];
    const bool near_lo = x - map.lo <= kStartInside, near_hi = map.hi - x <= kStartInside;
    across[k] = inward ? (near_lo && dx > 0.0) || (near_hi && dx < 0.0)
                       : (near_lo && x + dx < map.lo) || (near_hi && x + dx > map.hi);
  }
  return across;
}

// Ends a Ceres run on Ctrl-C (abort), and when a step from the seed's Jacobian failed: the stage runs Ceres again
// from the same point with a differenced one rather than shrinking the trust region around a model that may be
// wrong; on a rejected step that promised under kUnresolvedShare of the cost (from the coarse grid's Jacobian,
// the stage then confirms on its own grid); and at an accepted point whose Gauss-Newton step promises less than the
// function tolerance of the cost (a step Ceres would end on, one candidate's replay later). With `log.out`, writes
// one line per iteration there: the window's rmse at the current point (from the cost, the weak prior included), the
// values, the replays so far and the time since the stage began.
class StageCallback : public ceres::IterationCallback {
 public:
  StageCallback(const ReplayCost& cost, const PriorCost* prior, double function_tolerance,
                const ReplayResiduals& residuals, const double* u, const std::vector<bool>& held, const StageLog& log)
      : cost_(cost),
        prior_(prior),
        function_tolerance_(function_tolerance),
        residuals_(residuals),
        u_(u),
        held_(held),
        log_(log) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (InterruptRequested()) return ceres::SOLVER_ABORT;
    if (log_.out != nullptr) Report(s);
    if (!Rejected(s)) {
      point_cost_ = s.cost;
      // Ceres makes the Jacobian at an accepted point before it calls this (no replay here).
      if (cost_.Seeded()) return ceres::SOLVER_CONTINUE;
      double promise = 0.0, at = 0.0;
      std::vector<double> step;
      const std::vector<double> u(u_, u_ + residuals_.free_count());
      if (!GaussNewtonPromise(cost_, prior_, u, held_, &promise, &at, &step)) return ceres::SOLVER_CONTINUE;
      if (HoldAcrossBounds(u, step)) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
      if (s.iteration == 0) return ceres::SOLVER_CONTINUE;
      if (promise < function_tolerance_ * at) {
        predicted_ = true;
        if (log_.out != nullptr) {
          *log_.out << "  its Gauss-Newton step promises " << std::setprecision(3) << promise << " of a cost of " << at
                    << (cost_.Undifferenced() ? " (Jacobian on the coarser grid)" : "") << std::endl;
        }
        return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
      }
      return ceres::SOLVER_CONTINUE;
    }
    if (cost_.Seeded()) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    if (PredictedDecrease(s) < kUnresolvedShare * point_cost_) {  // false for NaN
      // From the coarse grid's Jacobian the stage's grid has the last word (SolveStage runs Ceres again).
      unresolved_ = !cost_.Undifferenced();
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    }
    return ceres::SOLVER_CONTINUE;
  }
  // Whether the run ended on a rejected step that promised less than kUnresolvedShare of the cost.
  bool unresolved() const { return unresolved_; }
  // Whether the run ended at an accepted point whose Gauss-Newton step promised less than the function tolerance.
  bool predicted() const { return predicted_; }
  // The coordinates to hold at their bounds from the point the run ended at (none: empty).
  const std::vector<bool>& hold() const { return hold_; }

 private:
  // Whether the Gauss-Newton step `step` at u pushes coordinates not yet held across a bound they lie at (kept in
  // hold_, written to the log): then the run ends, and the stage runs Ceres again with them held. At least one
  // coordinate stays free.
  bool HoldAcrossBounds(const std::vector<double>& u, const std::vector<double>& step) {
    std::vector<bool> across = AcrossBounds(residuals_.free(), u, step, false);
    std::size_t held = 0, more = 0;
    for (std::size_t k = 0; k < across.size(); ++k) {
      const bool already = k < held_.size() && held_[k];
      held += already ? 1 : 0;
      across[k] = across[k] && !already;
      more += across[k] ? 1 : 0;
    }
    if (more == 0 || held + more >= across.size()) return false;
    hold_ = std::move(across);
    if (log_.out != nullptr) {
      const ThermalParameters values = residuals_.Parameters(ToScaled(residuals_.free(), u.data()).data());
      for (std::size_t k = 0; k < hold_.size(); ++k) {
        if (!hold_[k]) continue;
        const FreeParameter& f = residuals_.free(k);
        const ParameterMap map = f.map();
        const bool low = map.ToScaled(u[k]) - map.lo <= kStartInside;
        *log_.out << "  " << f.name << " held at " << std::setprecision(4) << values.*(f.member)
                  << ": the Gauss-Newton step would take it across its bound " << (low ? f.lo : f.hi) << std::endl;
      }
    }
    return true;
  }

  void Report(const ceres::IterationSummary& s) const {
    std::ostream& o = *log_.out;
    o << "  iteration " << log_.done + s.iteration << ": ";
    if (Rejected(s)) {
      // The cost's change to the candidate and the change the linear model predicted, degC^2 (half the squared
      // residuals).
      o << "step rejected (cost " << std::showpos << std::setprecision(3) << -s.cost_change;
      if (std::isfinite(PredictedDecrease(s))) o << ", predicted " << -PredictedDecrease(s);
      o << std::noshowpos << "), staying at" << std::setprecision(4);  // (the summary's cost may be the trial's)
    } else {
      const double readings = static_cast<double>(std::max<std::size_t>(residuals_.size(), 1));
      o << "window rmse " << std::setprecision(4) << std::sqrt(2.0 * s.cost / readings) << " degC;";
    }
    const ThermalParameters values = residuals_.Parameters(ToScaled(residuals_.free(), u_).data());
    for (const FreeParameter& f : residuals_.free()) o << " " << f.name << " " << values.*(f.member);
    o << "; " << residuals_.replays() << " replays, " << std::setprecision(3)
      << std::chrono::duration<double>(std::chrono::steady_clock::now() - log_.start).count() << " s" << std::endl;
  }
  const ReplayCost& cost_;
  const PriorCost* prior_;
  double function_tolerance_;
  const ReplayResiduals& residuals_;
  const double* u_;  // Ceres' current point (update_state_every_iteration)
  const std::vector<bool>& held_;  // the coordinates the run holds
  const StageLog& log_;
  std::vector<bool> hold_;
  double point_cost_ = 0.0;  // the cost at the point Ceres stands on
  bool unresolved_ = false;
  bool predicted_ = false;
};

// How a Ceres run ended, besides its summary (StageCallback).
struct RunEnd {
  bool unresolved = false;  // on a step the replays could not resolve
  bool predicted = false;   // at a point whose Gauss-Newton step promised less than the function tolerance
  std::vector<bool> hold;   // at a point whose Gauss-Newton step crosses these coordinates' bounds (none: empty)
};

// One Ceres run from `u` (changed in place) with at most `iterations` iterations, the `held` coordinates kept; `end`
// tells how it ended.
ceres::Solver::Summary RunCeres(const ReplayResiduals& residuals, ReplayCost& cost, PriorCost* prior,
                                std::vector<double>& u, const std::vector<bool>& held, int iterations,
                                double function_tolerance, const StageLog& log, RunEnd* end) {
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;  // the stage's, over every run
  ceres::Problem problem(problem_options);
  problem.AddResidualBlock(&cost, nullptr, u.data());
  if (prior != nullptr) problem.AddResidualBlock(prior, nullptr, u.data());
  problem.SetManifold(u.data(), NewCappedStep(static_cast<int>(u.size()), held));  // owned by `problem`
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = iterations;
  solver.function_tolerance = function_tolerance;
  solver.parameter_tolerance = 1e-3;
  solver.gradient_tolerance = 1e-8;
  solver.logging_type = ceres::SILENT;
  solver.num_threads = 1;  // the parallelism is inside the cost (replays side by side)
  solver.update_state_every_iteration = true;  // the progress line reads u
  StageCallback callback(cost, prior, function_tolerance, residuals, u.data(), held, log);
  solver.callbacks.push_back(&callback);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  *end = {callback.unresolved(), callback.predicted(), callback.hold()};
  return summary;
}

// The stage's termination and message from its last Ceres run and how the stage ended: `confirmed` by the scenario
// grid's Gauss-Newton step, or as the last run ended (`end`; `coarse`: judged with the coarser grid's Jacobian).
void SetTermination(const ceres::Solver::Summary& last, bool confirmed, bool coarse, const RunEnd& end,
                    StageOutcome* outcome) {
  outcome->usable = last.IsSolutionUsable();
  outcome->termination = ceres::TerminationTypeToString(last.termination_type);
  outcome->message = last.message;
  if (confirmed) {
    outcome->termination = "CONVERGENCE";
    outcome->message = "the Jacobian differenced on the scenario's grid confirmed the answer: its Gauss-Newton step "
                       "promised to lower the cost by less than the function tolerance";
  } else if (end.unresolved) {
    outcome->termination = "CONVERGENCE";
    outcome->message = "a step the linear model promised to lower the cost by under 1 % failed: the replays' own "
                       "jumps between the solver's choices are larger (docs/REPLAY.md, \"The round trip's fit\")";
  } else if (end.predicted) {
    outcome->termination = "CONVERGENCE";
    outcome->message = std::string("the Gauss-Newton step from the last accepted point") +
                       (coarse ? " (its Jacobian on the coarser grid)" : "") +
                       " promised to lower the cost by less than the function tolerance";
  } else if (last.termination_type == ceres::USER_SUCCESS) {
    outcome->termination = "NO_CONVERGENCE";
    outcome->message = "the iterations ran out before a differenced Jacobian confirmed the answer";
  }
}

// Releases every held coordinate (returns true) when the Gauss-Newton step at u with all of them free moves one of
// the held ones away from its bound: the data then wants it inside, where Ceres can take it.
bool ReleaseHeld(const ReplayCost& cost, const PriorCost* prior, const std::vector<double>& u,
                 const std::vector<FreeParameter>& free, std::vector<bool>& held, std::ostream* progress) {
  if (std::none_of(held.begin(), held.end(), [](bool h) { return h; })) return false;
  double promise = 0.0, at = 0.0;
  std::vector<double> step;
  if (!GaussNewtonPromise(cost, prior, u, {}, &promise, &at, &step)) return false;
  const std::vector<bool> inward = AcrossBounds(free, u, step, true);
  bool release = false;
  for (std::size_t k = 0; k < held.size(); ++k) release = release || (held[k] && inward[k]);
  if (!release) return false;
  if (progress != nullptr) {
    *progress << "  released";
    for (std::size_t k = 0; k < held.size(); ++k) *progress << (held[k] ? " " + free[k].name : "");
    *progress << ": the Gauss-Newton step with every parameter free moves one away from its bound" << std::endl;
  }
  held.assign(held.size(), false);
  return true;
}

// Whether the Gauss-Newton step of the Jacobian differenced on the stage's grid at u (after RequestDifference(): n
// replays there) promises less than `tolerance` of the cost: the point a run on the coarser grid's Jacobians ended at
// on a step it could not resolve is then the answer.
bool ConfirmedOnStageGrid(const ReplayCost& cost, const PriorCost* prior, const std::vector<double>& u,
                          const std::vector<bool>& held, double tolerance, const ReplayResiduals& residuals,
                          std::ostream* progress) {
  double promise = 0.0, at = 0.0;
  if (!GaussNewtonPromise(cost, prior, u, held, &promise, &at) || promise >= tolerance * at) return false;
  if (progress != nullptr) {
    *progress << "  confirmed on the scenario's grid: its Gauss-Newton step promises " << std::setprecision(3)
              << promise << " of a cost of " << at << "; " << residuals.replays() << " replays" << std::endl;
  }
  return true;
}

// The stage's answer at u into `outcome`: the values, the held parameters, the Jacobians (the last one and the one
// at the answer, with how it was made), the data's cost and the count of each kind of Jacobian.
void RecordAnswer(const ReplayResiduals& residuals, const ReplayCost& cost, const PriorCost* prior,
                  const std::vector<double>& u, const std::vector<bool>& held, StageOutcome* outcome) {
  for (std::size_t k = 0; k < held.size(); ++k) {
    if (held[k]) outcome->held.push_back(residuals.free(k).name);
  }
  const std::vector<double> x = ToScaled(residuals.free(), u.data());
  outcome->error = cost.error();
  outcome->jacobian = cost.last_jacobian();
  const auto [jacobian, kind] = cost.JacobianOf(x);
  outcome->jacobian_at_x = *jacobian;
  outcome->differenced_at_x = kind == JacobianKind::kDifferenced;
  outcome->coarse_at_x = kind == JacobianKind::kCoarse;
  outcome->data_cost = outcome->runs.back().final_cost - (prior != nullptr ? prior->Cost(x) : 0.0);
  outcome->x = x;
  outcome->differenced = cost.Count(JacobianKind::kDifferenced);
  outcome->seeded = cost.Count(JacobianKind::kSeed);
  outcome->coarse = cost.Count(JacobianKind::kCoarse);
}

}  // namespace

StageOutcome SolveStage(const ReplayResiduals& residuals, const std::vector<double>& x_start, int max_iterations,
                        std::vector<double> seed, std::pair<double, std::vector<double>> prior,
                        std::ostream* progress, const ReplayResiduals* jacobian_grid) {
  const auto clock_start = std::chrono::steady_clock::now();
  const int replays_before = residuals.replays();
  const int coarse_before = jacobian_grid != nullptr ? jacobian_grid->replays() : 0;
  StageOutcome outcome;
  // Ceres runs unbounded on u; the bounds are kept by the maps x(u) (ParameterMap): on a bounded problem Ceres 2.1
  // evaluates every trust-region candidate through a projected line search that asks the gradient, i.e. a
  // differenced Jacobian (n + 1 replays) at each point it tries instead of one replay.
  std::vector<double> u = ToFree(residuals.free(), x_start);
  ReplayCost cost(residuals, std::move(seed), jacobian_grid);
  std::unique_ptr<PriorCost> prior_cost =
      prior.first > 0.0 ? std::make_unique<PriorCost>(residuals.free(), prior.second, prior.first) : nullptr;
  outcome.function_tolerance = 1e-3;
  int left = max_iterations;
  RunEnd end;
  // A run that ends on the seed's Jacobian (a failed step from it, or convergence judged on it) is run again from its
  // answer with a differenced Jacobian; the stage ends when a differenced one confirms the answer.
  // A run on the coarse grid's Jacobians that converged (Ceres' tolerances, or the Gauss-Newton step's promise) ends
  // the stage. One that ended otherwise (a failed step it could not resolve) is judged on the scenario's grid: when
  // that grid's Gauss-Newton step promises less than Ceres' function tolerance of the cost (a step Ceres would end
  // on), the stage ends there without trying it (a candidate costs a replay on the scenario's grid).
  // A coordinate the Gauss-Newton step pushes across a bound it lies at is held there: Ceres runs again from the same
  // point without it (its Jacobian kept: no replay). Once the stage would end, the held ones are released, once, when
  // the Gauss-Newton step with every coordinate free moves one of them away from its bound.
  bool confirmed = false, coarse_judged = false, released = false;
  std::vector<bool> held(residuals.free_count(), false);
  while (true) {
    const StageLog log{progress, clock_start, max_iterations - left};
    ceres::Solver::Summary summary =
        RunCeres(residuals, cost, prior_cost.get(), u, held, left, outcome.function_tolerance, log, &end);
    CheckInterrupt();
    left -= static_cast<int>(summary.iterations.size()) - 1;
    const bool usable = summary.IsSolutionUsable() && cost.error().empty();
    if (!end.hold.empty() && usable && left > 0) {
      for (std::size_t k = 0; k < held.size(); ++k) held[k] = held[k] || end.hold[k];
      outcome.runs.push_back(std::move(summary));
      continue;
    }
    // A point judged converged on the coarser grid's Jacobian is the answer: the scenario's grid judged the same
    // points with 3 more replays there and moved none of them (docs/REPLAY.md, "Jacobians on a coarser grid").
    coarse_judged = cost.Undifferenced() && !cost.Seeded() && usable &&
                    (end.predicted || summary.termination_type == ceres::CONVERGENCE);
    const bool again = !coarse_judged && !end.unresolved && usable && cost.Undifferenced() && left > 0 &&
                       (summary.termination_type == ceres::USER_SUCCESS ||
                        summary.termination_type == ceres::CONVERGENCE);
    outcome.runs.push_back(std::move(summary));
    if (!again) {
      if (!released && usable && left > 0 && ReleaseHeld(cost, prior_cost.get(), u, residuals.free(), held, progress)) {
        released = true;
        continue;
      }
      break;
    }
    cost.RequestDifference();
    if (jacobian_grid != nullptr &&
        ConfirmedOnStageGrid(cost, prior_cost.get(), u, held, outcome.function_tolerance, residuals, progress)) {
      confirmed = true;
      break;
    }
  }
  SetTermination(outcome.runs.back(), confirmed, coarse_judged, end, &outcome);
  RecordAnswer(residuals, cost, prior_cost.get(), u, held, &outcome);
  outcome.replays = residuals.replays() - replays_before;
  outcome.coarse_replays = jacobian_grid != nullptr ? jacobian_grid->replays() - coarse_before : 0;
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return outcome;
}

nlohmann::json StageSolverJson(const StageOutcome& stage) {
  int iterations = 0, successful = 0, unsuccessful = 0, residual_evaluations = 0, jacobian_evaluations = 0;
  for (const ceres::Solver::Summary& s : stage.runs) {
    iterations += std::max(static_cast<int>(s.iterations.size()) - 1, 0);  // none when the start's replay failed
    successful += s.num_successful_steps;
    unsuccessful += s.num_unsuccessful_steps;
    residual_evaluations += s.num_residual_evaluations;
    jacobian_evaluations += s.num_jacobian_evaluations;
  }
  return {{"termination", stage.termination},
          {"message", stage.message},
          {"iterations", iterations},
          {"runs", stage.runs.size()},
          {"initial_cost", stage.runs.front().initial_cost},
          {"final_cost", stage.runs.back().final_cost},
          {"function_tolerance", stage.function_tolerance},
          {"replays", stage.replays},
          {"jacobians", {{"differenced", stage.differenced}, {"seeded", stage.seeded}, {"coarse", stage.coarse}}},
          {"coarse_replays", stage.coarse_replays},
          {"held_at_bound", stage.held},
          {"successful_steps", successful},
          {"unsuccessful_steps", unsuccessful},
          {"residual_evaluations", residual_evaluations},
          {"jacobian_evaluations", jacobian_evaluations},
          {"report", stage.runs.back().BriefReport()}};
}

}  // namespace waam::analysis::internal
