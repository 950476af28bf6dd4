// `waam check` from a scenario file: plan the part (or read its program), then check the plan on the cell.
#include "analysis/check_command.h"

#include <iostream>

#include "analysis/import_command.h"
#include "analysis/scenario_plan.h"
#include "analysis/scenario.h"
#include "models/core/progress.h"
#include "planner/planar_planner.h"

namespace waam::analysis {

twin::CheckReport RunCheck(const CheckOptions& options) {
  const Scenario scenario = LoadScenario(options.scenario, options.overrides);
  planner::PlanResult planned;
  {
    Progress progress("plan", 0, "layers", options.quiet);
    planned = PlanScenarioOrProgram(scenario, &progress);
    progress.Finish();
  }
  // A program made elsewhere: what the twin did not execute, one line each.
  for (const std::string& warning : planned.warnings) std::cerr << "waam: warning: " << warning << "\n";
  CheckOptions with_target = options;
  with_target.target = &planned.mesh;
  return RunCheckOnPlan(scenario, planned.plan, with_target);
}

}  // namespace waam::analysis
