// The plan of a scenario: its part planned, or its program read.
#include "analysis/scenario_plan.h"

#include <iostream>

#include "analysis/program_file.h"
#include "analysis/stl_file.h"
#include "models/core/progress.h"
#include "planner/plan_scenario.h"

namespace waam::analysis {

planner::PlanResult PlanScenarioOrProgram(const Scenario& scenario, Progress* progress, ImportReport* report) {
  if (!scenario.program.present) return planner::PlanScenario(scenario, progress);
  const planner::ParsedProgram program =
      ReadProgramFile(scenario.program.file, scenario.program.format, planner::GcodeOptionsOf(scenario.program),
                      JbiOptionsOf(scenario), scenario.program.frames);
  ImportReport local;
  planner::PlanResult result = PlanFromProgram(scenario, program, report != nullptr ? report : &local);
  if (!scenario.program.target.empty()) {
    // The intended part, for the viewer and simulate's deviation measures (welded as a planned part's mesh is).
    result.mesh = ReadStl(scenario.program.target, 1e-4, &result.mesh_report);
  }
  if (progress != nullptr) progress->Finish();
  return result;
}

planner::PlanResult PlanForCommand(const Scenario& scenario, bool quiet) {
  Progress progress("plan", 0, "layers", quiet);
  planner::PlanResult planned = PlanScenarioOrProgram(scenario, &progress);
  // A program made elsewhere: what the twin did not execute, one line each.
  for (const std::string& warning : planned.warnings) std::cerr << "waam: warning: " << warning << "\n";
  return planned;
}

}  // namespace waam::analysis
