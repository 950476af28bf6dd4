// `waam run`: the scenario's steps in order, each into its own folder, and summary.json of their results.
#include "analysis/run_command.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>

#include "analysis/run_steps.h"
#include "analysis/scenario.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/core/output_lock.h"
#include "planner/scenario/scenario.h"

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

double PeakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux reports KiB
}

const internal::RunStep* FindStep(const std::string& name) {
  for (const internal::RunStep& step : internal::RunSteps()) {
    if (name == step.name) return &step;
  }
  return nullptr;
}

// The steps to run: the options' list, else the scenario's run.steps, else the default chain. Unknown names,
// repeats and a step listed before the step it needs are refused naming where the list came from.
std::vector<const internal::RunStep*> ResolveSteps(const Scenario& scenario, const RunOptions& options) {
  std::vector<std::string> names = options.steps;
  std::string where = "--steps";
  if (names.empty() && !scenario.run.steps.empty()) {
    names = scenario.run.steps;
    where = scenario.run.where;
  }
  if (names.empty()) {
    for (const internal::RunStep& step : internal::RunSteps()) {
      if (step.in_default_chain(scenario)) names.push_back(step.name);
    }
  }
  std::vector<const internal::RunStep*> steps;
  for (const std::string& name : names) {
    const internal::RunStep* step = FindStep(name);
    if (step == nullptr) {
      std::ostringstream known;
      for (const std::string& n : RunStepNames()) known << (known.tellp() > 0 ? ", " : "") << n;
      WAAM_THROW(where << ": unknown step '" << name << "', expected one of " << known.str());
    }
    WAAM_THROW_UNLESS(std::find(steps.begin(), steps.end(), step) == steps.end(),
                      where << ": step '" << name << "' is listed twice");
    // Steps that need the plan get it implicitly: the plan is computed whenever any step needs it.
    if (step->needs != nullptr) {
      const internal::RunStep* needed = FindStep(step->needs);
      const bool listed = std::find(steps.begin(), steps.end(), needed) != steps.end();
      const bool listed_later = std::find(names.begin(), names.end(), step->needs) != names.end();
      WAAM_THROW_UNLESS(listed || !listed_later,
                        where << ": step '" << name << "' needs '" << step->needs << "' before it");
      if (!listed) steps.push_back(needed);
    }
    steps.push_back(step);
  }
  return steps;
}

}  // namespace

std::vector<std::string> RunStepNames() {
  std::vector<std::string> names;
  for (const internal::RunStep& step : internal::RunSteps()) names.push_back(step.name);
  return names;
}

RunSummary RunScenario(const RunOptions& options) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const Scenario scenario = LoadScenario(options.scenario, options.overrides);
  const std::vector<const internal::RunStep*> steps = ResolveSteps(scenario, options);
  ClaimOutputDirectory(options.out_dir);
  // A summary.json from an earlier run must not describe this one while it is being replaced.
  std::error_code ec;
  fs::remove(options.out_dir / "summary.json", ec);

  RunSummary summary;
  summary.scenario = scenario.name;
  summary.expected_exit_code = scenario.run.expected_exit_code;
  internal::RunContext context{scenario, options, std::nullopt};
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const internal::RunStep& step = *steps[i];
    if (!options.quiet) std::fprintf(stderr, "run %s: step %zu/%zu %s\n", scenario.name.c_str(), i + 1,
                                     steps.size(), step.name);
    const Clock::time_point step_start = Clock::now();
    const internal::StepOutcome outcome = step.run(context, options.out_dir / step.name);
    StepSummary s;
    s.name = step.name;
    s.status = outcome.status;
    s.exit_code = outcome.exit_code;
    s.metrics = outcome.metrics;
    s.wall_s = std::chrono::duration<double>(Clock::now() - step_start).count();
    s.peak_rss_mb = PeakRssMb();
    summary.exit_code = std::max(summary.exit_code, s.exit_code);
    if (!options.quiet) std::fprintf(stderr, "run %s: %s %s in %.1f s\n", scenario.name.c_str(), step.name,
                                     s.status.c_str(), s.wall_s);
    summary.steps.push_back(std::move(s));
  }
  summary.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  WriteFileAtomic(options.out_dir / "summary.json", JsonText(RunSummaryToJson(summary)) + "\n");
  return summary;
}

nlohmann::json RunSummaryToJson(const RunSummary& summary) {
  nlohmann::json steps = nlohmann::json::array();
  nlohmann::json step_timing = nlohmann::json::object();
  for (const StepSummary& s : summary.steps) {
    const internal::RunStep* step = FindStep(s.name);
    steps.push_back({{"name", s.name},
                     {"status", s.status},
                     {"exit_code", s.exit_code},
                     {"outputs", s.name + "/" + (step ? step->main_output : "")},
                     {"metrics", s.metrics}});
    step_timing[s.name] = {{"wall_s", s.wall_s}, {"peak_rss_mb", s.peak_rss_mb}};
  }
  return {
      {"scenario", summary.scenario},
      {"exit_code", summary.exit_code},
      {"expected_exit_code", summary.expected_exit_code},
      {"as_expected", summary.exit_code == summary.expected_exit_code},
      {"steps", steps},
      {"timing", {{"total_s", summary.wall_s}, {"steps", step_timing}}},
  };
}

}  // namespace waam::analysis
