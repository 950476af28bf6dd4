// `waam run <scenario.yaml> -o <dir>`: command-line options of the one-command scenario run.
#include <cstdio>
#include <memory>

#include "analysis/run_command.h"
#include "app/commands.h"

namespace waam::app {

void AddRunCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::RunOptions>();
  CLI::App* command = app.add_subcommand(
      "run",
      "Run a scenario end to end in one command: plan the weld path, check it on the robot cell, deposit it in the\n"
      "voxel twin (and any optional step the scenario asks for), with progress on stderr. The steps come from the\n"
      "scenario's optional `run:` section (`steps: [plan, check, simulate]`; `expected_exit_code: 3` for a planted\n"
      "cell fault), else the default chain plan, check, simulate. The plan is computed once and shared by the steps.\n"
      "Writes to the output directory:\n"
      "  plan/, check/, simulate/   each step's outputs, as `waam plan|check|simulate` write them\n"
      "  summary.json               scenario, exit_code, expected_exit_code, as_expected, steps [{name, status\n"
      "                             (ok | violations), exit_code, outputs, metrics}], timing {total_s, steps {name:\n"
      "                             {wall_s, peak_rss_mb}}}; written last (its presence marks a complete run); all\n"
      "                             but `timing` is identical between two runs of the same scenario.\n"
      "Exit code: the largest of the steps' (3 when check found violations; the other steps still run).");
  command->add_option("scenario", options->scenario, "Scenario YAML file")->required();
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing)")->required();
  command->add_option("--set", options->overrides,
                      "Override a scenario setting, key.path=value (repeatable), e.g. --set simulation.voxel_mm=1");
  command->add_option("--steps", options->steps,
                      "Steps to run instead of the scenario's (comma or space separated), e.g. --steps plan,simulate")
      ->delimiter(',');
  command->add_flag("-q,--quiet", options->quiet, "No progress on stderr");
  command->add_flag("!--no-images", options->images, "Do not draw the steps' PNGs (nor the check step's viewer.html)");
  command->callback([options, runner] {
    *runner = [options] {
      const analysis::RunSummary summary = analysis::RunScenario(*options);
      for (const analysis::StepSummary& step : summary.steps) {
        std::printf("%-9s %-10s %6.1f s  %7.0f MiB peak\n", step.name.c_str(), step.status.c_str(), step.wall_s,
                    step.peak_rss_mb);
      }
      std::printf("%s: exit code %d (expected %d) in %.1f s -> %s\n", summary.scenario.c_str(), summary.exit_code,
                  summary.expected_exit_code, summary.wall_s, (options->out_dir / "summary.json").string().c_str());
      return summary.exit_code;
    };
  });
}

}  // namespace waam::app
