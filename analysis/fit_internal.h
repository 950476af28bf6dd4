// Internal to `waam fit`: helpers shared by its branches, and the void-length branch.
#pragma once

#include <iosfwd>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "analysis/fit_command.h"
#include "models/core/csv.h"
#include "models/fit/fit_stats.h"
#include "models/voids/void_length_model.h"

namespace ceres {
class Manifold;
}  // namespace ceres

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

// The smooth map from an unbounded Ceres variable u to a free thermal parameter in scaled units x = value / scale
// (analysis/fit_thermal_map.cc). Lower bound only (hi = +inf): x = lo + exp(u), a log scale, as convection and table
// contact span orders of magnitude. Two bounds: the logistic x = lo + (hi - lo) / (1 + exp(-u)). Every u maps strictly
// inside the bounds (to them only where exp under- or overflows) and dx/du > 0 there, so no parameter loses its
// gradient at a bound.
struct ParameterMap {
  double lo = 0.0;                                          // lower bound, scaled units
  double hi = std::numeric_limits<double>::infinity();      // upper bound, scaled units (+inf: none)
  // x(u), scaled units.
  double ToScaled(double u) const;
  // u(x) for lo < x < hi; x on or beyond a bound is first moved kStartInside inside it. WAAM_DEMAND on a NaN.
  double ToFree(double x) const;
  // dx/du at u (> 0 wherever x(u) is not on a bound).
  double Slope(double u) const;
};
// The largest change of Ceres' variable u per step (a factor e^2 = 7.4 in x - lo above a lower bound).
inline constexpr double kMaxFreeStep = 2.0;
// A new manifold (Ceres owns it once set) that caps each coordinate of Ceres' steps in u at +-kMaxFreeStep and keeps
// the `held` ones (true; fewer than n) where they are.
ceres::Manifold* NewCappedStep(int n, const std::vector<bool>& held = {});
// How far inside a bound a start value on it is moved (scaled units: 1 % of the parameter's scale).
inline constexpr double kStartInside = 0.01;

// A parameter is reported undetermined when one standard deviation exceeds this fraction of its value.
inline constexpr double kUndeterminedFraction = 0.25;

// What the identifiability report of a thermal fit is computed from.
struct IdentifiabilityInput {
  std::vector<std::string> names;   // the free parameters
  std::vector<double> scales;       // x = value / scale
  std::vector<double> values;       // fitted values, own units
  std::vector<double> jacobian;     // d residual / d x at the fitted point, m x n row-major, degC per scaled unit
                                    // (x = value / scale: physical units, not the fit's free variable u)
  std::size_t m = 0;                // readings (data residuals)
  double data_cost = 0.0;           // 1/2 sum of the data residuals squared, degC^2 (the prior's part excluded)
  double prior_weight = 0.0;        // --prior W, degC per scaled unit (0: none)
};
// The covariance of the free parameters, s^2 (J^T J + W^2 I)^+ with s^2 = 2 cost / (m - n) (Gauss-Newton; the
// pseudo-inverse leaves a null direction out): `standard_deviation` and `correlation` by name, `undetermined` (one
// standard deviation over kUndeterminedFraction of the value), and from the data alone (J^T J scaled to a unit
// diagonal) its `condition_number` and `weakest` combination, one standard deviation along it in each parameter's
// units; `noise_c` = s, `readings` = m, `prior_weight_c` = W. A parameter with a zero column (not felt in the
// window) is left out of every figure and listed in `blind` and `undetermined`.
// WAAM_DEMAND on inconsistent sizes.
nlohmann::json ThermalIdentifiability(const IdentifiabilityInput& in);
// Prints the report `id` (null: nothing): standard deviations (with the grid of their Jacobian, `jacobian_cell_mm`,
// where it is not `cell_mm`), strong correlations (|r| > 0.9), the weakest combination and what is undetermined.
void PrintIdentifiability(const nlohmann::json& id, double cell_mm, std::ostream& out);

}  // namespace waam::analysis::internal
