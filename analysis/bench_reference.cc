// The papers' published figures (models/data/reference_figures.csv) next to the bench's own results.
#include <array>
#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

#include "analysis/bench_command.h"
#include "models/core/csv.h"
#include "models/core/enum_names.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/fit/model_file.h"

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

// How a row's `compare` column turns the bench's metric into the published quantity: as it is (an empty cell), per
// layer (divided by the plan's layers), or as the reduction in % against another scenario ("reduction_pct_vs:NAME").
enum class CompareMode { kValue, kPerLayer, kReductionPctVs };
constexpr std::array<EnumName<CompareMode>, 3> EnumNames(CompareMode) {
  return {{{CompareMode::kValue, ""}, {CompareMode::kPerLayer, "per_layer"},
           {CompareMode::kReductionPctVs, "reduction_pct_vs"}}};
}

// A row's `compare` cell: the mode and, for reduction_pct_vs, the other scenario's name. Throws InputError naming the
// file and line for another mode.
std::pair<CompareMode, std::string> ParseCompare(const std::string& cell, const std::string& where) {
  const std::size_t colon = cell.find(':');
  const std::optional<CompareMode> mode = ParseEnum<CompareMode>(std::string_view(cell).substr(0, colon));
  WAAM_THROW_UNLESS(mode && (*mode == CompareMode::kReductionPctVs) == (colon != std::string::npos),
                    where << ": compare = '" << cell
                          << "': must be empty, per_layer or reduction_pct_vs:SCENARIO");
  return {*mode, colon == std::string::npos ? std::string() : cell.substr(colon + 1)};
}

// The bench entry of scenario `name` (by scenario name or id), or nullptr.
const nlohmann::json* FindEntry(const nlohmann::json& scenarios, const std::string& name) {
  for (const nlohmann::json& e : scenarios) {
    if (e.value("id", "") == name || (e.contains("scenario") && e["scenario"].is_string() && e["scenario"] == name)) {
      return &e;
    }
  }
  return nullptr;
}

// The metric `key` of step `step` in a bench entry, or null.
nlohmann::json StepMetric(const nlohmann::json& entry, const std::string& step, const std::string& key) {
  for (const nlohmann::json& s : entry.value("steps", nlohmann::json::array())) {
    if (s.value("name", "") == step && s.contains("metrics") && s["metrics"].contains(key)) return s["metrics"][key];
  }
  return nullptr;
}

}  // namespace

nlohmann::json ReferenceComparison(const nlohmann::json& scenarios) {
  const fs::path data_dir = models::DefaultModelPath("csw").parent_path();
  const CsvTable table = CsvTable::Read(data_dir / "reference_figures.csv");
  auto col = [&](const char* name) { return table.Strings(name); };
  const auto ids = col("id"), sources = col("source"), quantities = col("quantity"), published = col("published"),
             values = col("published_value"), units = col("unit"), names = col("scenario"), steps = col("step"),
             metrics = col("metric"), compares = col("compare");
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t i = 0; i < table.rows(); ++i) {
    nlohmann::json ours = nullptr;
    const std::string& step = steps[i];
    if (step.rfind("model:", 0) == 0) {
      const fs::path file = data_dir / (step.substr(6) + ".json");
      std::error_code ec;
      if (fs::is_regular_file(file, ec)) {
        const nlohmann::json model = nlohmann::json::parse(ReadFile(file));
        const nlohmann::json::json_pointer pointer(metrics[i]);
        if (model.contains(pointer)) ours = model.at(pointer);
      }
    } else if (const nlohmann::json* entry = FindEntry(scenarios, names[i])) {
      ours = StepMetric(*entry, step, metrics[i]);
      const auto [compare, other_name] =
          ParseCompare(compares[i], table.source() + ":" + std::to_string(table.line(i)));
      if (ours.is_number() && compare == CompareMode::kPerLayer) {
        const nlohmann::json layers = StepMetric(*entry, "plan", "layers");
        ours = layers.is_number() && layers.get<double>() > 0 ? nlohmann::json(ours.get<double>() / layers.get<double>())
                                                              : nlohmann::json(nullptr);
      } else if (ours.is_number() && compare == CompareMode::kReductionPctVs) {
        const nlohmann::json* other = FindEntry(scenarios, other_name);
        const nlohmann::json theirs = other ? StepMetric(*other, step, metrics[i]) : nlohmann::json(nullptr);
        ours = theirs.is_number() && theirs.get<double>() != 0.0
                   ? nlohmann::json(100.0 * (1.0 - ours.get<double>() / theirs.get<double>()))
                   : nlohmann::json(nullptr);
      }
    }
    nlohmann::json published_value = nullptr;
    if (!values[i].empty()) published_value = std::stod(values[i]);
    rows.push_back({{"id", ids[i]},
                    {"source", sources[i]},
                    {"quantity", quantities[i]},
                    {"published", published[i]},
                    {"published_value", published_value},
                    {"ours", ours},
                    {"unit", units[i]},
                    {"scenario", names[i].empty() ? step : names[i]}});
  }
  return rows;
}

}  // namespace waam::analysis
