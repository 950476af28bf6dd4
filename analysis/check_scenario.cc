// `waam check` from a scenario file: plan the part (or read its program), then check the plan on the cell.
#include "analysis/check_command.h"


#include "analysis/import_command.h"
#include "analysis/scenario_plan.h"
#include "analysis/scenario.h"
#include "planner/planar_planner.h"

namespace waam::analysis {

twin::CheckReport RunCheck(const CheckOptions& options) {
  const Scenario scenario = LoadScenario(options.scenario, options.overrides);
  planner::PlanResult planned = PlanForCommand(scenario, options.quiet);
  CheckOptions with_target = options;
  with_target.target = &planned.mesh;
  return RunCheckOnPlan(scenario, planned.plan, with_target);
}

}  // namespace waam::analysis
