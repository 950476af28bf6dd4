// The optional `waam run` steps: junction void tuning (rib-webs, issue 6) and the compensation loop (issue 8).
#include <string>

#include "analysis/distortion_command.h"
#include "analysis/run_steps.h"
#include "analysis/tune_voids_command.h"
#include "models/core/files.h"

namespace waam::analysis::internal {
namespace fs = std::filesystem;

// Runs `waam tune-voids` on the scenario into the step's folder (tune.json, junction pictures).
StepOutcome RunTuneVoidsStep(RunContext& context, const fs::path& step_dir) {
  auto options = StepOptions<TuneVoidsOptions>(context, step_dir);
  options.images = context.options.images;
  const TuneVoidsResult result = RunTuneVoids(options);
  StepOutcome outcome;
  int converged = 0;
  nlohmann::json shifts = nlohmann::json::object();
  for (const JunctionTuning& junction : result.junctions) {
    converged += junction.converged ? 1 : 0;
    shifts[junction.junction_class] = {{"shift_mm", junction.tuned.shift_mm},
                                       {"void_volume_mm3", junction.tuned.void_volume_mm3},
                                       {"plain_void_volume_mm3", junction.plain.void_volume_mm3}};
  }
  outcome.metrics = {{"junction_classes", result.junctions.size()}, {"converged", converged}, {"junctions", shifts}};
  return outcome;
}

// Runs `waam compensate` on the scenario into the step's folder. A loop that does not reach its tolerance is not a
// failed run (the iterations are the result); its status is reported.
StepOutcome RunCompensateStep(RunContext& context, const fs::path& step_dir) {
  auto options = StepOptions<CompensateOptions>(context, step_dir);
  options.images = context.options.images;
  const twin::CompensationResult result = RunCompensate(options);
  StepOutcome outcome;
  nlohmann::json iterations = nlohmann::json::array();
  for (const twin::CompensationIteration& it : result.iterations) iterations.push_back(it.max_abs_deviation_mm);
  outcome.metrics = {{"status", result.status},
                     {"converged", result.converged},
                     {"tolerance_mm", result.tolerance_mm},
                     {"max_abs_deviation_mm", iterations}};
  return outcome;
}

}  // namespace waam::analysis::internal
