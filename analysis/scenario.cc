// The whole scenario, composed from each module's section parsers.
#include "analysis/scenario.h"

#include <cmath>

#include "analysis/scenario_keys.h"
#include "models/core/error.h"
#include "planner/program/program_section.h"
#include "planner/scenario/scenario_document.h"
#include "twin/cell/cell_section.h"

namespace waam::analysis {

namespace {

// A JSON value as the YAML node a file with the same content would give: maps, sequences and scalars (numbers in
// JSON's shortest round-trip form; NaN and infinities as YAML's .nan and .inf, which the range checks refuse).
YAML::Node ToYaml(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::object: {
      YAML::Node node(YAML::NodeType::Map);
      for (const auto& [key, child] : value.items()) node[key] = ToYaml(child);
      return node;
    }
    case nlohmann::json::value_t::array: {
      YAML::Node node(YAML::NodeType::Sequence);
      for (const nlohmann::json& child : value) node.push_back(ToYaml(child));
      return node;
    }
    case nlohmann::json::value_t::string:
      return YAML::Node(value.get<std::string>());
    case nlohmann::json::value_t::null:
      return YAML::Node(YAML::NodeType::Null);
    case nlohmann::json::value_t::number_float: {
      const double x = value.get<double>();
      if (std::isnan(x)) return YAML::Node(".nan");
      if (std::isinf(x)) return YAML::Node(x > 0 ? ".inf" : "-.inf");
      return YAML::Node(value.dump());
    }
    default:
      return YAML::Node(value.dump());  // booleans and integers
  }
}

// Every module parses its own sections from the scenario's top-level map.
Scenario ParseScenario(YamlMap& top) {
  Scenario scenario;
  static_cast<planner::Scenario&>(scenario) = planner::ParsePlannerSections(top);
  const std::filesystem::path dir = scenario.dir;
  scenario.cell = twin::ParseCellSection(top, dir);
  twin::ParseSimulationSection(top, &scenario.simulation, dir);
  internal::ParseRunSection(top, &scenario.run);
  internal::ParsePlaceSection(top, &scenario.place);
  internal::ParseThermalSection(top, &scenario.thermal);
  internal::ParseReplaySection(top, dir, &scenario.replay);
  scenario.program = planner::ParseProgramSection(top, dir);
  // The CSW radius clamp is one rule for the planner's speed and the twin's bead width (simulation section).
  scenario.process.csw_min_radius_mm = scenario.simulation.csw_min_radius_mm;
  top.CheckNoUnknownKeys();
  internal::CheckThermalScenario(scenario.process, scenario.thermal);
  internal::LoadThermalMaterials(dir, &scenario.thermal);
  return scenario;
}

}  // namespace

Scenario LoadScenario(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  CheckOverrideKeys(overrides);
  YamlMap top = planner::LoadScenarioTop(file, overrides);
  return ParseScenario(top);
}

Scenario ScenarioFromJson(const nlohmann::json& document, const std::filesystem::path& base_dir,
                          const std::vector<std::string>& overrides) {
  const std::filesystem::path name = base_dir / kScenarioDocumentName;
  WAAM_THROW_UNLESS(document.is_object(), name.string() << ": a scenario is a mapping of sections (name, part, "
                                                           "slicing, ...), got " << document.type_name());
  std::error_code ec;
  WAAM_THROW_UNLESS(std::filesystem::is_directory(base_dir, ec),
                    "base_dir: folder " << base_dir.string() << " not found");
  CheckOverrideKeys(overrides);
  YamlMap top = planner::ScenarioTop(ToYaml(document), name, overrides);
  return ParseScenario(top);
}

}  // namespace waam::analysis
