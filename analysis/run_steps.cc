// The built-in `waam run` steps (plan, check, simulate) and the step registry.
#include "analysis/run_steps.h"

#include <algorithm>

#include "analysis/check_command.h"
#include "analysis/plan_command.h"
#include "analysis/scenario.h"
#include "analysis/simulate_command.h"
#include "analysis/viewer.h"
#include "models/core/files.h"

namespace waam::analysis::internal {
namespace fs = std::filesystem;

namespace {

bool Always(const Scenario&) { return true; }
bool WhenListed(const Scenario&) { return false; }  // only when run.steps or --steps names it
bool WhenThermal(const Scenario& scenario) { return scenario.thermal.given; }  // the scenario has a thermal: section

}  // namespace

// To add a step (e.g. tune_voids when the scenario has a tuning section, compensate when it has a compensation
// section): write `StepOutcome RunXStep(RunContext&, const fs::path&)` in its own file, declare it in run_steps.h
// and add one line here; `needs` names the step whose results it reads from the context.
const std::vector<RunStep>& RunSteps() {
  static const std::vector<RunStep> steps = {
      {"plan", nullptr, Always, RunPlanStep, "plan.json"},
      {"check", "plan", Always, RunCheckStep, "check.json"},
      {"simulate", "plan", Always, RunSimulateStep, "simulate.json"},
      {"tune_voids", nullptr, WhenListed, RunTuneVoidsStep, "tune.json"},
      {"compensate", nullptr, WhenListed, RunCompensateStep, "compensate.json"},
      {"thermal", "plan", WhenThermal, RunThermalStep, "thermal.json"},
  };
  return steps;
}

nlohmann::json PickMetrics(const nlohmann::json& document, const std::vector<std::string>& keys) {
  nlohmann::json metrics = nlohmann::json::object();
  for (const std::string& key : keys) {
    const nlohmann::json::json_pointer pointer(key);
    if (document.contains(pointer)) metrics[key.substr(1)] = document.at(pointer);
  }
  return metrics;
}

StepOutcome RunPlanStep(RunContext& context, const fs::path& step_dir) {
  auto options = StepOptions<PlanOptions>(context, step_dir);
  options.layer_images = context.options.images;
  nlohmann::json document;
  context.planned = RunPlan(options, &document);
  StepOutcome outcome;
  outcome.metrics = PickMetrics(document, {"/layers", "/passes", "/path_elements", "/weld_length_mm",
                                           "/travel_length_mm", "/estimated_time_s", "/bead_width_mm",
                                           "/bead_height_mm", "/layer_height_mm", "/travel_speed_mm_min",
                                           "/uncovered/pct", "/timeline"});
  int max_passes = 0;
  for (int passes : context.planned->stats.passes_per_layer) max_passes = std::max(max_passes, passes);
  outcome.metrics["max_passes_per_layer"] = max_passes;
  context.results["plan"] = std::move(document);
  return outcome;
}

StepOutcome RunCheckStep(RunContext& context, const fs::path& step_dir) {
  auto options = StepOptions<CheckOptions>(context, step_dir);
  options.images = context.options.images;
  options.target = &context.planned->mesh;
  const twin::CheckReport report = RunCheckOnPlan(context.scenario, context.planned->plan, options);
  nlohmann::json document = nlohmann::json::parse(ReadFile(step_dir / "check.json"));
  StepOutcome outcome;
  outcome.status = report.ok ? "ok" : "violations";
  outcome.exit_code = report.ok ? 0 : 3;
  outcome.metrics = PickMetrics(document, {"/ok", "/ik", "/samples", "/violation_count", "/min_joint_margin_deg",
                                           "/max_joint_speed_ratio", "/min_j5_deg", "/max_torch_tilt_deg",
                                           "/duration_s"});
  nlohmann::json kinds = nlohmann::json::object();
  for (const twin::CheckViolation& v : report.violations) {
    const std::string kind(NameOf(v.kind));
    kinds[kind] = kinds.value(kind, 0) + 1;
  }
  outcome.metrics["violations_by_kind"] = kinds;
  context.results["check"] = std::move(document);
  return outcome;
}

StepOutcome RunSimulateStep(RunContext& context, const fs::path& step_dir) {
  auto options = StepOptions<SimulateOptions>(context, step_dir);
  options.images = context.options.images;
  const twin::TwinResult result = SimulatePlanned(context.scenario, *context.planned, options);
  // The check step's viewer, when it ran before, grows the deposited part.
  const fs::path viewer = step_dir.parent_path() / "check" / "viewer.html";
  if (context.results.contains("check") && fs::is_regular_file(viewer)) {
    AddDepositToViewer(viewer, result.depositor, &result.deviation);
  }
  nlohmann::json document = SimulationToJson(context.scenario, *context.planned, result);
  document.erase("performance");  // timings and memory: summary.json keeps them under `timing`
  StepOutcome outcome;
  outcome.metrics = PickMetrics(
      document, {"/voxels", "/deposited_volume_mm3", "/expected_volume_mm3", "/volume_error_pct",
                 "/deviation/min_mm", "/deviation/max_mm", "/deviation/rms_mm", "/voids/count",
                 "/voids/volume_mm3", "/valleys/count", "/ra_mm", "/waviness_mm", "/boundary_lag_mm",
                 "/build_time_s", "/not_applicable", "/notes"});
  context.results["simulate"] = std::move(document);
  return outcome;
}

}  // namespace waam::analysis::internal
