// `waam check` from a scenario file: plan the part, then check the plan on the cell.
#include "analysis/check_command.h"

#include "analysis/import_command.h"
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
  return RunCheckOnPlan(scenario, planned.plan, options);
}

}  // namespace waam::analysis
