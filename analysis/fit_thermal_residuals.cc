// `waam fit thermal`'s free parameters and residuals: which thermal parameters may be fitted, their scaled values,
// and the replays of the window whose thermocouple errors Ceres minimises.
#include "analysis/fit_thermal_cost.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "models/core/error.h"

namespace waam::analysis::internal {

namespace {

constexpr double kNoBound = std::numeric_limits<double>::infinity();

}  // namespace

const std::vector<FreeParameter>& AllThermalFree() {
  static const std::vector<FreeParameter> all = {
      {"efficiency", &ThermalParameters::efficiency, 1.0, 0.2, 1.0, "process.arc.efficiency"},
      {"convection", &ThermalParameters::convection_w_m2k, 10.0, 0.0, kNoBound, "thermal.convection_w_m2k"},
      {"contact", &ThermalParameters::table_conductance_w_m2k, 100.0, 0.0, kNoBound,
       "thermal.table.conductance_w_m2k"},
      {"emissivity", &ThermalParameters::emissivity, 1.0, 0.02, 1.0, "thermal.emissivity"},
      {"clamps", &ThermalParameters::clamp_factor, 1.0, 0.0, kNoBound, "thermal.clamp_conductance_factor"},
  };
  return all;
}

std::vector<FreeParameter> ResolveThermalFree(const std::vector<std::string>& names) {
  WAAM_THROW_UNLESS(!names.empty(), "--free: name at least one of efficiency, convection, contact, emissivity, "
                                    "clamps");
  std::vector<FreeParameter> free;
  for (const std::string& name : names) {
    const auto& all = AllThermalFree();
    const auto it = std::find_if(all.begin(), all.end(), [&](const auto& f) { return f.name == name; });
    WAAM_THROW_UNLESS(it != all.end(), "--free '" << name << "': must be efficiency, convection, contact, "
                                                     "emissivity or clamps");
    for (const FreeParameter& f : free) WAAM_THROW_UNLESS(f.name != name, "--free '" << name << "': given twice");
    free.push_back(*it);
  }
  return free;
}

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

bool SameParameters(const ThermalParameters& a, const ThermalParameters& b) {
  return std::all_of(AllThermalFree().begin(), AllThermalFree().end(), [&](const FreeParameter& f) {
    const double u = a.*f.member, v = b.*f.member;
    return u == v || std::abs(u - v) <= 1e-12 * std::max(std::abs(u), std::abs(v));
  });
}

ReplayResiduals::ReplayResiduals(const ReplayModel& model, const std::vector<FreeParameter>& free,
                                 const ThermalParameters& start, std::pair<double, double> window)
    : model_(&model), free_(free), start_(start), window_(window) {
  // A probe not yet in metal at the start gives 0 there later too.
  for (std::size_t p = 0; p < model.probes.size(); ++p) {
    for (std::size_t i = 0; i < model.log.time_s.size(); ++i) {
      const double t = model.log.time_s[i];
      if (t >= window.first && t <= window.second && std::isfinite(model.log.probe_c[p][i])) used_.push_back({p, i});
    }
  }
}

ThermalParameters ReplayResiduals::Parameters(const double* x) const {
  ThermalParameters p = start_;
  for (std::size_t k = 0; k < free_.size(); ++k) {
    p.*(free_[k].member) = x[k] * free_[k].scale;
    WAAM_DEMAND(p.*(free_[k].member) >= free_[k].lo && p.*(free_[k].member) <= free_[k].hi);
  }
  return p;
}

std::size_t ReplayResiduals::Run(const double* x, double* residuals, twin::SolverChoices* record,
                                 std::shared_ptr<const twin::SolverChoices> follow) const {
  auto run = std::make_unique<ReplayRun>(*model_, Parameters(x));
  if (record != nullptr) run->RecordChoices();
  if (follow != nullptr) run->FollowChoices(std::move(follow));
  run->AdvanceThrough(window_.second);
  const std::vector<std::vector<double>> probe_c = run->ProbesTo(window_.second);
  if (record != nullptr) *record = run->TakeChoices();
  // Recording replays run one at a time (the parallel ones follow), so they are kept without a race. The first, when
  // made at the start values, is continued to the log's end at once and only its result kept (one simulation less
  // held through the fit).
  if (keep_runs_ && record != nullptr) {
    const bool first = start_whole_ == nullptr && recent_runs_.empty();
    if (first && SameParameters(run->parameters(), start_)) {
      run->AdvanceTo(std::numeric_limits<double>::infinity());
      start_whole_ = std::make_unique<ReplaySimulation>(run->Result());
    } else {
      if (recent_runs_.size() == kRecentRuns) recent_runs_.erase(recent_runs_.begin());
      recent_runs_.push_back(std::move(run));
    }
  }
  ++replays_;
  std::size_t missing = 0;
  for (std::size_t r = 0; r < used_.size(); ++r) {
    const auto [p, i] = used_[r];
    const double s = probe_c[p][i];
    residuals[r] = std::isfinite(s) ? s - model_->log.probe_c[p][i] : 0.0;
    missing += std::isfinite(s) ? 0 : 1;
  }
  return missing;
}

ReplaySimulation ReplayResiduals::WholeLogAt(const ThermalParameters& p) const {
  if (start_whole_ != nullptr && SameParameters(p, start_)) return *start_whole_;
  for (auto it = recent_runs_.rbegin(); it != recent_runs_.rend(); ++it) {
    ReplayRun& run = **it;
    if (!SameParameters(p, run.parameters())) continue;
    run.AdvanceTo(std::numeric_limits<double>::infinity());
    return run.Result();
  }
  return SimulateReplay(*model_, p);
}

}  // namespace waam::analysis::internal
