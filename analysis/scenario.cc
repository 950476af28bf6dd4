// The whole scenario, composed from each module's section parsers.
#include "analysis/scenario.h"

#include "planner/program/program_section.h"
#include "planner/scenario/yaml_fields.h"
#include "twin/cell/cell_section.h"

namespace waam::analysis {

Scenario LoadScenario(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  planner::internal::YamlMap top = planner::internal::LoadScenarioTop(file, overrides);
  Scenario scenario;
  static_cast<planner::Scenario&>(scenario) = planner::internal::ParsePlannerSections(top);
  const std::filesystem::path dir = scenario.dir;
  scenario.cell = twin::internal::ParseCellSection(top, dir);
  twin::internal::ParseSimulationSection(top, &scenario.simulation, dir);
  internal::ParseRunSection(top, &scenario.run);
  internal::ParsePlaceSection(top, &scenario.place);
  internal::ParseThermalSection(top, &scenario.thermal);
  scenario.program = planner::internal::ParseProgramSection(top, dir);
  // The CSW radius clamp is one rule for the planner's speed and the twin's bead width (simulation section).
  scenario.process.csw_min_radius_mm = scenario.simulation.csw_min_radius_mm;
  top.CheckNoUnknownKeys();
  internal::CheckThermalScenario(scenario.process, scenario.thermal);
  internal::LoadThermalMaterials(dir, &scenario.thermal);
  return scenario;
}

}  // namespace waam::analysis
