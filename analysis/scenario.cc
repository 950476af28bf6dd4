// The whole scenario, composed from each module's section parsers.
#include "analysis/scenario.h"

#include "analysis/scenario_keys.h"
#include "planner/program/program_section.h"
#include "planner/scenario/scenario_document.h"
#include "twin/cell/cell_section.h"

namespace waam::analysis {

Scenario LoadScenario(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  CheckOverrideKeys(overrides);
  YamlMap top = planner::LoadScenarioTop(file, overrides);
  Scenario scenario;
  static_cast<planner::Scenario&>(scenario) = planner::ParsePlannerSections(top);
  const std::filesystem::path dir = scenario.dir;
  scenario.cell = twin::ParseCellSection(top, dir);
  twin::ParseSimulationSection(top, &scenario.simulation, dir);
  internal::ParseRunSection(top, &scenario.run);
  internal::ParsePlaceSection(top, &scenario.place);
  internal::ParseThermalSection(top, &scenario.thermal);
  scenario.program = planner::ParseProgramSection(top, dir);
  // The CSW radius clamp is one rule for the planner's speed and the twin's bead width (simulation section).
  scenario.process.csw_min_radius_mm = scenario.simulation.csw_min_radius_mm;
  top.CheckNoUnknownKeys();
  internal::CheckThermalScenario(scenario.process, scenario.thermal);
  internal::LoadThermalMaterials(dir, &scenario.thermal);
  internal::LoadThermalShape(dir, &scenario.thermal);
  return scenario;
}

}  // namespace waam::analysis
