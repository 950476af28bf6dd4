// Internal to `waam fit`: helpers shared by its branches, and the void-length branch.
#pragma once

#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "analysis/fit_command.h"
#include "models/core/csv.h"
#include "models/fit/fit_stats.h"
#include "models/voids/void_length_model.h"

namespace waam::analysis::internal {

// Role -> column name: the model's defaults overridden by the "role=column" items of --columns. Throws InputError
// for a malformed item or an unknown role.
std::map<std::string, std::string> ResolveColumns(const FitOptions& options);
// The data record of a fit: file, provenance lines, columns, rows.
models::DataSource MakeSource(const FitOptions& options, const CsvTable& table,
                              const std::map<std::string, std::string>& columns);
// `dof_note` replaces the "(sqrt(SSE / (n - p)))" explanation when p is not the parameter count (a network).
void PrintStats(std::ostream& out, const models::FitStats& stats, const std::string& unit,
                const std::string& dof_note = "");
void PrintSolver(std::ostream& out, const models::SolverReport& report);
// Prints the failure, or writes `model` to options.output atomically and says so.
FitOutcome Finish(bool ok, const std::string& message, nlohmann::json model, const FitOptions& options,
                  std::ostream& out);

// Reads junctions from `table` using the void-length column roles of `options`. Throws InputError naming the file,
// line and column for a bad value (eta not a whole number >= 1, angles outside [0, 360]).
std::vector<models::JunctionSample> ReadJunctions(const FitOptions& options, const CsvTable& table);

// Fits the chosen kind on every row, cross-validates network and baseline, predicts the hold-out junctions from a
// model trained on the other rows, prints all of it and writes the JSON.
FitOutcome RunVoidLength(const FitOptions& options, const CsvTable& table, std::ostream& out);

// `waam fit distortion`: plans and deposits options.scenario in the twin, fits the free distortion parameters to the
// scan options.data (point-to-surface residuals), prints the fit and writes the model JSON with a "fit" record.
// Throws InputError for bad input; a fit Ceres did not converge comes back with ok = false and nothing written.
FitOutcome RunFitDistortion(const FitOptions& options, std::ostream& out);

}  // namespace waam::analysis::internal
