// Goodness-of-fit statistics and the solver and data records every fitted model carries in its JSON.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/core/enum_names.h"

namespace waam::models {

// Goodness of fit of a model with `num_params` parameters on n samples.
struct FitStats {
  std::size_t n = 0;
  int num_params = 0;
  double sse = 0.0;       // residual sum of squares [unit^2 of the fitted quantity]
  double r2 = 0.0;        // 1 - SSE / SST (coefficient of determination)
  double rmse = 0.0;      // sqrt(SSE / n) [unit of the fitted quantity]
  double rmse_dof = 0.0;  // sqrt(SSE / (n - num_params)) [unit]; NaN if n <= num_params
};

// Statistics of `predicted` against `measured` (same size, at least one value). Throws std::invalid_argument on a
// size mismatch (a programming error).
FitStats ComputeFitStats(const std::vector<double>& measured, const std::vector<double>& predicted, int num_params);

nlohmann::json ToJson(const FitStats& stats);
// Reads what ToJson wrote; `where` names the file for errors. Throws InputError on a missing or non-numeric key.
FitStats FitStatsFromJson(const nlohmann::json& j, const std::string& where);

// How Ceres ended (ceres::TerminationType, named as ceres::TerminationTypeToString names it); kNotRun ("") for a
// report of no solve.
enum class SolverTermination { kNotRun, kConvergence, kNoConvergence, kFailure, kUserSuccess, kUserFailure };
constexpr std::array<EnumName<SolverTermination>, 6> EnumNames(SolverTermination) {
  return {{{SolverTermination::kNotRun, ""},
           {SolverTermination::kConvergence, "CONVERGENCE"},
           {SolverTermination::kNoConvergence, "NO_CONVERGENCE"},
           {SolverTermination::kFailure, "FAILURE"},
           {SolverTermination::kUserSuccess, "USER_SUCCESS"},
           {SolverTermination::kUserFailure, "USER_FAILURE"}}};
}
WAAM_ENUM_JSON(SolverTermination)
// The termination Ceres names `ceres_name` (ceres::TerminationTypeToString); a name outside the table is the code's
// mistake (WAAM_DEMAND).
SolverTermination TerminationNamed(std::string_view ceres_name);

// How the solver ended (a copy of the parts of ceres::Solver::Summary a user needs).
struct SolverReport {
  bool usable = false;       // ceres::Solver::Summary::IsSolutionUsable()
  SolverTermination termination = SolverTermination::kNotRun;
  std::string message;       // Ceres' message, or why the fit was refused
  int iterations = 0;
  double initial_cost = 0.0;  // 0.5 * sum of squared residuals
  double final_cost = 0.0;
  double seconds = 0.0;       // wall time of the solve (printed, not written to model files)
};

nlohmann::json ToJson(const SolverReport& report);
// Reads what ToJson wrote; `where` names the file for errors. Throws InputError for an unknown termination name.
SolverReport SolverReportFromJson(const nlohmann::json& j, const std::string& where);

// Where a model's data came from: the CSV file, its '#' provenance lines, which columns played which role.
struct DataSource {
  std::string file;                              // path as given to `waam fit`
  std::vector<std::string> provenance;           // the file's comment lines
  std::map<std::string, std::string> columns;    // role -> column name
  std::size_t rows = 0;                          // rows used by the fit
  std::string selection;                         // which rows were left out and why (empty: all rows used)
};

nlohmann::json ToJson(const DataSource& source);
DataSource DataSourceFromJson(const nlohmann::json& j);

// The record a fitted model keeps about its fit (empty for a model built from typed-in parameters).
struct FitInfo {
  FitStats stats;
  SolverReport solver;
  DataSource data;
  bool fitted = false;
};

nlohmann::json ToJson(const FitInfo& info);
FitInfo FitInfoFromJson(const nlohmann::json& model, const std::string& where);

}  // namespace waam::models
