// The plan of a scenario, whichever way it comes: planned from its part, or read from its program: section.
#pragma once

#include "analysis/import_command.h"
#include "analysis/scenario.h"
#include "planner/planar_planner.h"

namespace waam {
class Progress;
}

namespace waam::analysis {

// The plan of the scenario: from its program: section when it has one (read with the scenario's cell and program
// settings, its target STL as the mesh), else planned from its part (planner::PlanScenario). `report` (may be null)
// is filled for a program. Throws InputError for a part that cannot be planned or a program that cannot be read.
planner::PlanResult PlanScenarioOrProgram(const Scenario& scenario, Progress* progress, ImportReport* report = nullptr);

// PlanScenarioOrProgram for a command: a "plan" progress bar on stderr (none when `quiet`), and each line of the
// program that the twin does not execute printed to stderr as a warning. Throws as PlanScenarioOrProgram.
planner::PlanResult PlanForCommand(const Scenario& scenario, bool quiet);

}  // namespace waam::analysis
