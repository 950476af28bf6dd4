// Goodness-of-fit statistics and their JSON form.
#include "models/fit/fit_stats.h"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "models/core/error.h"
#include "models/fit/model_file.h"

namespace waam::models {
namespace {
// JSON has no NaN: an undefined statistic is written as null and read back as NaN.
nlohmann::json NumberOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
double NumberOrNaN(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::numeric_limits<double>::quiet_NaN();
}
}  // namespace

FitStats ComputeFitStats(const std::vector<double>& measured, const std::vector<double>& predicted, int num_params) {
  if (measured.size() != predicted.size() || measured.empty()) {
    throw std::invalid_argument("ComputeFitStats: measured and predicted must have the same, non-zero size");
  }
  FitStats s;
  s.n = measured.size();
  s.num_params = num_params;
  double mean = 0.0;
  for (double y : measured) mean += y;
  mean /= static_cast<double>(s.n);
  double sst = 0.0;
  for (std::size_t i = 0; i < s.n; ++i) {
    const double r = measured[i] - predicted[i];
    s.sse += r * r;
    sst += (measured[i] - mean) * (measured[i] - mean);
  }
  s.r2 = sst > 0.0 ? 1.0 - s.sse / sst : std::numeric_limits<double>::quiet_NaN();
  s.rmse = std::sqrt(s.sse / static_cast<double>(s.n));
  const long dof = static_cast<long>(s.n) - num_params;
  s.rmse_dof = dof > 0 ? std::sqrt(s.sse / static_cast<double>(dof)) : std::numeric_limits<double>::quiet_NaN();
  return s;
}

nlohmann::json ToJson(const FitStats& s) {
  return {{"n", s.n},           {"num_params", s.num_params}, {"sse", NumberOrNull(s.sse)},
          {"r2", NumberOrNull(s.r2)}, {"rmse", NumberOrNull(s.rmse)}, {"rmse_dof", NumberOrNull(s.rmse_dof)}};
}

FitStats FitStatsFromJson(const nlohmann::json& j, const std::string& where) {
  FitStats s;
  s.n = static_cast<std::size_t>(JsonNumber(j, "/n", where + " stats"));
  s.num_params = static_cast<int>(JsonNumber(j, "/num_params", where + " stats"));
  s.sse = NumberOrNaN(j, "sse");
  s.r2 = NumberOrNaN(j, "r2");
  s.rmse = NumberOrNaN(j, "rmse");
  s.rmse_dof = NumberOrNaN(j, "rmse_dof");
  return s;
}

nlohmann::json ToJson(const SolverReport& r) {
  return {{"usable", r.usable},         {"termination", r.termination}, {"message", r.message},
          {"iterations", r.iterations}, {"initial_cost", NumberOrNull(r.initial_cost)},
          {"final_cost", NumberOrNull(r.final_cost)}};  // no wall time: identical inputs, identical files
}

SolverTermination TerminationNamed(std::string_view ceres_name) {
  const std::optional<SolverTermination> termination = ParseEnum<SolverTermination>(ceres_name);
  WAAM_DEMAND(termination.has_value() && *termination != SolverTermination::kNotRun);
  return *termination;
}

SolverReport SolverReportFromJson(const nlohmann::json& j, const std::string& where) {
  SolverReport r;
  r.usable = j.value("usable", false);
  const std::string termination = j.value("termination", "");
  const std::optional<SolverTermination> parsed = ParseEnum<SolverTermination>(termination);
  WAAM_THROW_UNLESS(parsed, where << ": /fit/solver/termination = '" << termination << "': must be one of "
                                  << EnumNameList<SolverTermination>());
  r.termination = *parsed;
  r.message = j.value("message", "");
  r.iterations = j.value("iterations", 0);
  r.initial_cost = NumberOrNaN(j, "initial_cost");
  r.final_cost = NumberOrNaN(j, "final_cost");
  return r;
}

nlohmann::json ToJson(const DataSource& d) {
  return {{"file", d.file}, {"provenance", d.provenance}, {"columns", d.columns}, {"rows", d.rows}, {"selection", d.selection}};
}

DataSource DataSourceFromJson(const nlohmann::json& j) {
  DataSource d;
  d.file = j.value("file", "");
  d.provenance = j.value("provenance", std::vector<std::string>{});
  d.columns = j.value("columns", std::map<std::string, std::string>{});
  d.rows = j.value("rows", std::size_t{0});
  d.selection = j.value("selection", "");
  return d;
}

nlohmann::json ToJson(const FitInfo& info) {
  if (!info.fitted) return nullptr;
  return {{"stats", ToJson(info.stats)}, {"solver", ToJson(info.solver)}, {"data", ToJson(info.data)}};
}

FitInfo FitInfoFromJson(const nlohmann::json& model, const std::string& where) {
  FitInfo info;
  if (!model.contains("fit") || model["fit"].is_null()) return info;
  const nlohmann::json& fit = model["fit"];
  WAAM_THROW_UNLESS(fit.is_object() && fit.contains("stats"), where << ": /fit must be an object with 'stats'");
  info.fitted = true;
  info.stats = FitStatsFromJson(fit["stats"], where);
  if (fit.contains("solver")) info.solver = SolverReportFromJson(fit["solver"], where);
  if (fit.contains("data")) info.data = DataSourceFromJson(fit["data"]);
  return info;
}

}  // namespace waam::models
