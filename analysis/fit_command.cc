// `waam fit`: CSV columns -> samples -> Ceres fit -> summary on stdout and model JSON on disk.
#include "analysis/fit_command.h"

#include <cmath>
#include <iomanip>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>

#include "analysis/fit_internal.h"
#include "analysis/replay_command.h"
#include "models/bead/bead_temperature_model.h"
#include "models/bead/csw_model.h"
#include "models/bead/speed_height_model.h"
#include "models/bead/width_height_model.h"
#include "models/core/csv.h"
#include "models/core/error.h"
#include "models/fit/model_file.h"

namespace waam::analysis {
namespace {
namespace m = waam::models;
using Columns = std::vector<std::pair<std::string, std::string>>;

// The role -> default column table of each model read from a CSV (distortion reads a scan, thermal a scenario).
Columns DefaultColumns(FitModel model) {
  switch (model) {
    case FitModel::kCsw:
      return {{"speed", "travel_speed_mm_per_min"}, {"radius", "curvature_radius_mm"}, {"width", "width_mm"}};
    case FitModel::kSpeedHeight: return {{"speed", "travel_speed_mm_per_min"}, {"height", "height_mm"}};
    case FitModel::kWidthHeight:
      return {{"height", "height_mm"}, {"width", "width_mm"}, {"speed", "travel_speed_mm_per_min"}};
    case FitModel::kBeadTemperature: return {{"temperature", "interpass_c"}, {"height", "height_mm"}, {"width", "width_mm"}};
    case FitModel::kVoidLength:
      return {{"eta", "eta"},           {"theta1", "theta1_deg"},      {"theta2", "theta2_deg"}, {"theta3", "theta3_deg"},
              {"theta4", "theta4_deg"}, {"void", "void_length_mm"}, {"label", "group"}};
    case FitModel::kDistortion:
    case FitModel::kThermal: return {};
  }
  return {};
}

}  // namespace

std::map<std::string, std::string> internal::ResolveColumns(const FitOptions& options) {
  const Columns defaults = DefaultFitColumns(options.model);
  std::map<std::string, std::string> resolved(defaults.begin(), defaults.end());
  for (const std::string& item : options.columns) {
    const std::size_t eq = item.find('=');
    WAAM_THROW_UNLESS(eq != std::string::npos && eq > 0 && eq + 1 < item.size(),
                      "--columns '" << item << "': expected role=column, e.g. speed=v_mm_per_min");
    const std::string role = item.substr(0, eq);
    if (!resolved.count(role)) {
      std::string roles;
      for (const auto& [r, c] : defaults) roles += (roles.empty() ? "" : ", ") + r;
      WAAM_THROW("--columns '" << item << "': unknown role '" << role << "' for " << NameOf(options.model)
                               << " (roles: " << roles << ")");
    }
    resolved[role] = item.substr(eq + 1);
  }
  return resolved;
}

m::DataSource internal::MakeSource(const FitOptions& options, const CsvTable& table,
                         const std::map<std::string, std::string>& columns) {
  m::DataSource source;
  source.file = options.data.string();
  source.provenance = table.provenance();
  source.columns = columns;
  source.rows = table.rows();
  return source;
}

void internal::PrintStats(std::ostream& out, const m::FitStats& s, const std::string& unit,
                          const std::string& dof_note) {
  out << "  n        = " << s.n << "\n"
      << "  r2       = " << std::setprecision(6) << s.r2 << "\n"
      << "  rmse     = " << s.rmse << " " << unit << "\n"
      << "  rmse_dof = " << s.rmse_dof << " " << unit << "  ("
      << (dof_note.empty() ? "sqrt(SSE / (n - " + std::to_string(s.num_params) + "))" : dof_note) << ")\n";
}

void internal::PrintSolver(std::ostream& out, const m::SolverReport& r) {
  out << "  solver   = Ceres " << NameOf(r.termination) << ", " << r.iterations << " iterations, "
      << std::setprecision(3) << r.seconds * 1e3 << " ms\n";
}

FitOutcome internal::Finish(bool ok, const std::string& message, nlohmann::json model, const FitOptions& options,
                  std::ostream& out) {
  FitOutcome outcome{ok, message, std::move(model)};
  if (!ok) {
    out << "fit failed: " << message << "\n";
    return outcome;
  }
  m::WriteModelJson(options.output, outcome.model);
  out << "wrote " << options.output.string() << "\n";
  return outcome;
}

namespace {
using namespace internal;

const m::SpeedRange* RangeOption(const FitOptions& options, m::SpeedRange* storage) {
  if (!options.speed_range) return nullptr;
  *storage = {options.speed_range->first, options.speed_range->second};
  storage->Validate("--speed-range");
  return storage;
}

// Rows kept by --speed-range (all rows without it); excluded rows are printed and recorded in `source`.
std::vector<std::size_t> SelectRows(const FitOptions& options, const CsvTable& table, const std::string& speed_column,
                                    m::DataSource* source, std::ostream& out) {
  std::vector<std::size_t> keep;
  if (!options.speed_range) {
    for (std::size_t i = 0; i < table.rows(); ++i) keep.push_back(i);
    return keep;
  }
  const auto [lo, hi] = *options.speed_range;
  const std::vector<double> speed = table.Numbers(speed_column);
  std::ostringstream excluded;
  for (std::size_t i = 0; i < table.rows(); ++i) {
    if (speed[i] >= lo && speed[i] <= hi) {
      keep.push_back(i);
    } else {
      excluded << (excluded.tellp() > 0 ? ", " : "") << "line " << table.line(i) << " (" << speed[i] << " mm/min)";
    }
  }
  if (excluded.tellp() > 0) {
    std::ostringstream selection;
    selection << "rows with " << speed_column << " outside --speed-range [" << lo << ", " << hi
              << "] mm/min excluded: " << excluded.str();
    source->selection = selection.str();
    out << "  " << source->selection << "\n";
  }
  source->rows = keep.size();
  return keep;
}

std::vector<double> Subset(const std::vector<double>& values, const std::vector<std::size_t>& keep) {
  std::vector<double> out;
  for (std::size_t i : keep) out.push_back(values[i]);
  return out;
}

FitOutcome RunCsw(const FitOptions& options, const CsvTable& table, std::ostream& out) {
  const auto cols = ResolveColumns(options);
  m::DataSource source = MakeSource(options, table, cols);
  const auto keep = SelectRows(options, table, cols.at("speed"), &source, out);
  m::CswSamples s{Subset(table.Numbers(cols.at("speed")), keep),
                  Subset(table.Numbers(cols.at("radius"), /*allow_infinity=*/true), keep),
                  Subset(table.Numbers(cols.at("width")), keep)};
  m::SpeedRange storage;
  const m::CswFit fit = m::FitCsw(s, source, RangeOption(options, &storage));
  const m::CswParams& p = fit.model.params();
  out << "CSW model w = m v^(-1/3) + p / r + t  (w, t mm; v mm/min; r mm)\n" << std::setprecision(6)
      << "  params   : m = " << p.m << ", p = " << p.p << ", t = " << p.t << "\n";
  PrintStats(out, fit.model.fit().stats, "mm");
  PrintSolver(out, fit.model.fit().solver);
  return Finish(fit.ok, fit.message, fit.model.ToJson(), options, out);
}

FitOutcome RunSpeedHeight(const FitOptions& options, const CsvTable& table, std::ostream& out) {
  const auto cols = ResolveColumns(options);
  m::DataSource source = MakeSource(options, table, cols);
  const auto keep = SelectRows(options, table, cols.at("speed"), &source, out);
  m::SpeedHeightSamples s{Subset(table.Numbers(cols.at("speed")), keep), Subset(table.Numbers(cols.at("height")), keep)};
  m::SpeedRange storage;
  const m::SpeedHeightFit fit =
      m::FitSpeedHeight(s, source,
                        options.space, RangeOption(options, &storage));
  out << "speed-height power law v = a h^b  (v mm/min, h mm), residuals in " << NameOf(options.space) << " v\n"
      << std::setprecision(6) << "  params   : a = " << fit.model.params().a << ", b = " << fit.model.params().b
      << "\n";
  PrintStats(out, fit.model.fit().stats, "mm/min");
  out << "  r2 of ln v = " << std::setprecision(6) << fit.model.log_stats().r2 << "  (what a log-log power trendline reports)\n";
  PrintSolver(out, fit.model.fit().solver);
  return Finish(fit.ok, fit.message, fit.model.ToJson(), options, out);
}

FitOutcome RunWidthHeight(const FitOptions& options, const CsvTable& table, std::ostream& out) {
  const auto cols = ResolveColumns(options);
  m::DataSource source = MakeSource(options, table, cols);
  if (!options.speed_range) source.columns.erase("speed");
  const auto keep = SelectRows(options, table, cols.at("speed"), &source, out);
  m::WidthHeightSamples s{Subset(table.Numbers(cols.at("height")), keep), Subset(table.Numbers(cols.at("width")), keep)};
  const m::WidthHeightFit fit = m::FitWidthHeight(s, source, options.degree);
  out << "width-height polynomial w = sum c_k h^k, degree " << options.degree << "  (w mm, h mm)\n  params   :";
  out << std::setprecision(6);
  for (std::size_t k = 0; k < fit.model.coefficients().size(); ++k) {
    out << (k ? "," : "") << " c" << k << " = " << fit.model.coefficients()[k];
  }
  out << "\n";
  PrintStats(out, fit.model.fit().stats, "mm");
  PrintSolver(out, fit.model.fit().solver);
  return Finish(fit.ok, fit.message, fit.model.ToJson(), options, out);
}

FitOutcome RunBeadTemperature(const FitOptions& options, const CsvTable& table, std::ostream& out) {
  const auto cols = ResolveColumns(options);
  WAAM_THROW_UNLESS(std::isfinite(options.reference_c) && options.reference_c >= -50.0 && options.reference_c <= 2000.0,
                    "--reference-c " << options.reference_c << ": must be in [-50, 2000] degC");
  const m::DataSource source = MakeSource(options, table, cols);
  const m::BeadTemperatureSamples s{table.Numbers(cols.at("temperature")), table.Numbers(cols.at("height")),
                                    table.Numbers(cols.at("width"))};
  const m::BeadTemperatureFit fit = m::FitBeadTemperature(s, source, options.reference_c, options.volume_conserving);
  const m::BeadTemperatureParams& p = fit.model.params();
  out << "bead-temperature model h = h_ref (1 + k_h (T - T_ref)), "
      << (p.volume_conserving ? "w = w_ref / (1 + k_h (T - T_ref))" : "w = w_ref (1 + k_w (T - T_ref))")
      << "  (h, w mm; T degC), T_ref = " << p.reference_c << " degC\n"
      << std::setprecision(6) << "  params   : h_ref = " << fit.model.h_ref_mm() << " mm, k_h = " << p.height_per_k
      << " 1/K, w_ref = " << fit.model.w_ref_mm() << " mm";
  if (!p.volume_conserving) out << ", k_w = " << p.width_per_k << " 1/K";
  out << "\n  range    : [" << p.min_c << ", " << p.max_c << "] degC\n  height:\n";
  PrintStats(out, fit.model.fit().stats, "mm");
  out << "  width:\n";
  PrintStats(out, fit.model.width_stats(), "mm");
  PrintSolver(out, fit.model.fit().solver);
  return Finish(fit.ok, fit.message, fit.model.ToJson(), options, out);
}

}  // namespace

FitModel ParseFitModel(const std::string& name) {
  const std::optional<FitModel> model = ParseEnum<FitModel>(name);
  WAAM_THROW_UNLESS(model, "unknown model '" << name << "': must be one of " << EnumNameList<FitModel>());
  return *model;
}

std::vector<std::pair<std::string, std::string>> DefaultFitColumns(FitModel model) { return DefaultColumns(model); }

FitOutcome RunFit(const FitOptions& options, std::ostream& out) {
  if (options.model == FitModel::kDistortion) return internal::RunFitDistortion(options, out);
  if (options.model == FitModel::kThermal) return internal::RunFitThermal(options, out);
  WAAM_THROW_UNLESS(!options.output.empty(), "-o/--output: the model JSON file to write is required");
  const CsvTable table = CsvTable::Read(options.data);
  // Every required column must exist before any value is read, so a misnamed column is reported as such.
  for (const auto& [role, column] : internal::ResolveColumns(options)) {
    const bool optional = role == "label" || (role == "speed" && options.model == FitModel::kWidthHeight);
    if (!optional) table.ColumnIndex(column);
  }
  out << "waam fit " << NameOf(options.model) << ": " << options.data.string() << " (" << table.rows() << " rows)\n";
  switch (options.model) {
    case FitModel::kCsw: return RunCsw(options, table, out);
    case FitModel::kSpeedHeight: return RunSpeedHeight(options, table, out);
    case FitModel::kWidthHeight: return RunWidthHeight(options, table, out);
    case FitModel::kBeadTemperature: return RunBeadTemperature(options, table, out);
    case FitModel::kVoidLength:
    case FitModel::kDistortion:
    case FitModel::kThermal: break;
  }
  return internal::RunVoidLength(options, table, out);
}

}  // namespace waam::analysis
