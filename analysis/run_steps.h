// The registry of `waam run` steps: what each step needs, when the default chain includes it, and how it runs.
// Adding a step = one function (in its own file) and one line in the table of RunSteps() (analysis/run_steps.cc).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "analysis/run_command.h"
#include "analysis/scenario.h"
#include "planner/planar_planner.h"
#include "planner/scenario/scenario.h"

namespace waam::analysis::internal {

// What the steps of one run share: the scenario, the options, and what earlier steps produced.
struct RunContext {
  const Scenario& scenario;
  const RunOptions& options;
  std::optional<planner::PlanResult> planned;  // set by the plan step
  nlohmann::json results = nlohmann::json::object();  // each finished step's full JSON document, by step name
};

// What a step returns (status ok | violations; exit code 0 or 3; its key metrics, no timings).
struct StepOutcome {
  std::string status = "ok";
  int exit_code = 0;
  nlohmann::json metrics = nlohmann::json::object();
};

using StepFunction = StepOutcome (*)(RunContext& context, const std::filesystem::path& step_dir);

struct RunStep {
  const char* name;                              // the step's name in run.steps and its output folder
  const char* needs;                             // a step that must have run before (nullptr: none)
  bool (*in_default_chain)(const Scenario&);  // true: run when the scenario lists no steps
  StepFunction run;
  const char* main_output;                       // the file marking the step complete, relative to its folder
};

// The options of a step's command (PlanOptions, CheckOptions, SimulateOptions, TuneVoidsOptions, CompensateOptions)
// with what every command takes from the run: its scenario file, --set overrides and quiet flag, and `step_dir` as the
// output folder. The step sets its own picture flag; everything else keeps the command's defaults.
template <typename CommandOptions>
CommandOptions StepOptions(const RunContext& context, const std::filesystem::path& step_dir) {
  CommandOptions options;
  options.scenario = context.options.scenario;
  options.out_dir = step_dir;
  options.overrides = context.options.overrides;
  options.quiet = context.options.quiet;
  return options;
}

// The registered steps in their default order.
const std::vector<RunStep>& RunSteps();

// The built-in steps (analysis/run_steps.cc).
StepOutcome RunPlanStep(RunContext& context, const std::filesystem::path& step_dir);
StepOutcome RunCheckStep(RunContext& context, const std::filesystem::path& step_dir);
StepOutcome RunSimulateStep(RunContext& context, const std::filesystem::path& step_dir);
// The optional steps (analysis/run_optional_steps.cc), run only when listed: tune_voids (waam tune-voids) and
// compensate (waam compensate with its default options).
StepOutcome RunTuneVoidsStep(RunContext& context, const std::filesystem::path& step_dir);
StepOutcome RunCompensateStep(RunContext& context, const std::filesystem::path& step_dir);
// The thermal step (analysis/run_thermal_step.cc): waam thermal on the plan step's plan, in the default chain when
// the scenario has a thermal: section.
StepOutcome RunThermalStep(RunContext& context, const std::filesystem::path& step_dir);

// Copies the keys listed in `keys` (JSON pointers such as "/deviation/rms_mm") from `document` into a flat object
// named by the pointers without the leading slash ("deviation/rms_mm"); missing keys are left out.
nlohmann::json PickMetrics(const nlohmann::json& document, const std::vector<std::string>& keys);

}  // namespace waam::analysis::internal
