// `waam run`: one scenario end to end (plan -> check -> simulate -> optional steps) with summary.json of the steps.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace waam::analysis {

struct RunOptions {
  std::filesystem::path scenario;      // scenario YAML
  std::filesystem::path out_dir;       // output directory; step outputs go to <out_dir>/<step>/
  std::vector<std::string> overrides;  // "key.path=value" scenario overrides (--set)
  std::vector<std::string> steps;      // steps to run instead of the scenario's `run.steps` (empty: the scenario's)
  bool quiet = false;                  // no progress bars and no step lines on stderr
  bool images = true;                  // pictures of the steps (layer PNGs, cell, joints, height and deviation maps)
};

// One step's outcome as summary.json reports it.
struct StepSummary {
  std::string name;          // plan | check | simulate | ...
  std::string status;        // ok | violations | skipped (a step it needs did not run)
  int exit_code = 0;         // the exit code the step alone would give (0, or 3 for check violations)
  nlohmann::json metrics;    // the step's key numbers (deterministic: no timings)
  double wall_s = 0.0;       // wall time of the step, s
  double peak_rss_mb = 0.0;  // peak resident memory of the process once the step finished, MiB
};

struct RunSummary {
  std::string scenario;       // scenario name
  std::vector<StepSummary> steps;
  int exit_code = 0;          // the largest step exit code
  int expected_exit_code = 0; // the scenario's run.expected_exit_code
  double wall_s = 0.0;        // whole run, s
};

// Runs the scenario's steps in order and writes <out_dir>/<step>/... and <out_dir>/summary.json (last, atomically;
// its presence marks a complete run). Throws InputError for a bad scenario or an unknown step name.
RunSummary RunScenario(const RunOptions& options);

// summary.json: scenario, exit_code, expected_exit_code, as_expected, steps [{name, status, exit_code, outputs,
// metrics}], and `timing` {total_s, steps {name: {wall_s, peak_rss_mb}}} — the only non-deterministic part.
nlohmann::json RunSummaryToJson(const RunSummary& summary);

// The names of the registered steps, in their default order.
std::vector<std::string> RunStepNames();

}  // namespace waam::analysis
