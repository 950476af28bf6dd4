// RunSimulate: the planning step of `waam simulate` (kept apart so the twin's outputs can be tested on hand-made
// plans).
#include <iostream>

#include "analysis/import_command.h"
#include "analysis/scenario_plan.h"
#include "analysis/scenario.h"
#include "analysis/simulate_command.h"
#include "models/core/progress.h"

namespace waam::analysis {

twin::TwinMeasures RunSimulate(const SimulateOptions& options) {
  const Scenario scenario = LoadScenario(options.scenario, options.overrides);
  planner::PlanResult planned;
  {
    Progress progress("plan", 0, "layers", options.quiet);
    planned = PlanScenarioOrProgram(scenario, &progress);
    progress.Finish();
  }
  // A program made elsewhere: what the twin did not execute, one line each.
  for (const std::string& warning : planned.warnings) std::cerr << "waam: warning: " << warning << "\n";
  return SimulatePlanned(scenario, planned, options).measures;
}

}  // namespace waam::analysis
