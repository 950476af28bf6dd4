// The `thermal` step of `waam run`: the thermal model along the build's timeline (waam thermal) on the planned part.
#include "analysis/run_steps.h"
#include "analysis/thermal_command.h"
#include "analysis/viewer.h"

namespace waam::analysis::internal {
namespace fs = std::filesystem;

// Runs `waam thermal` on the plan step's plan into the step's folder; its metrics are the build time, the waits, the
// highest interpass temperature and the peak temperature.
StepOutcome RunThermalStep(RunContext& context, const fs::path& step_dir) {
  auto options = StepOptions<ThermalOptions>(context, step_dir);
  options.images = context.options.images;
  const ThermalRunResult result = ThermalPlanned(context.scenario, context.planned->plan, options);
  // The check step's viewer, when it ran before, colours the part by temperature.
  const fs::path viewer = step_dir.parent_path() / "check" / "viewer.html";
  if (context.results.contains("check") && fs::is_regular_file(viewer)) AddThermalToViewer(viewer, result);
  nlohmann::json document = ThermalToJson(context.scenario, result);
  document["solver"].erase("wall_s");  // timings: summary.json keeps them under `timing`
  StepOutcome outcome;
  outcome.metrics = PickMetrics(document, {"/build_time_s", "/total_wait_s", "/max_interpass_c", "/peak_c",
                                           "/interpass_wait_s", "/energy_balance/relative_error"});
  context.results["thermal"] = std::move(document);
  return outcome;
}

}  // namespace waam::analysis::internal
