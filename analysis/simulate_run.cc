// RunSimulate: the planning step of `waam simulate` (kept apart so the twin's outputs can be tested on hand-made
// plans).

#include "analysis/import_command.h"
#include "analysis/scenario_plan.h"
#include "analysis/scenario.h"
#include "analysis/simulate_command.h"

namespace waam::analysis {

twin::TwinMeasures RunSimulate(const SimulateOptions& options) {
  const Scenario scenario = LoadScenario(options.scenario, options.overrides);
  planner::PlanResult planned = PlanForCommand(scenario, options.quiet);
  return SimulatePlanned(scenario, planned, options).measures;
}

}  // namespace waam::analysis
