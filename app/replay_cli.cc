// `waam thermal replay <scenario.yaml> -o <dir>`: command-line options of the replay of a build's process log.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "analysis/replay_command.h"
#include "app/commands.h"

namespace waam::app {

CLI::App* AddThermalReplayCommand(CLI::App& thermal, CommandRunner* runner) {
  auto options = std::make_shared<analysis::ReplayOptions>();
  CLI::App* command = thermal.add_subcommand(
      "replay",
      "Replay a build's process log (CSV: time, arc power or voltage x current, arc on, head x y z, thermocouples)\n"
      "through the thermal model and compare every thermocouple (docs/REPLAY.md). The scenario's replay: section\n"
      "names the log, its columns, frame, bead and probes {NAME: {column, at_mm}}; thermal: and process.arc\n"
      "(efficiency) as for `waam thermal`. Between two rows the arc (on in the first) welds along the head's move\n"
      "with power x efficiency, else the part cools. Rows the log cannot vouch for (gaps, repeated times, an\n"
      "all-zero first row, empty thermocouple cells) are listed on stderr and in replay.json log_issues.\n"
      "Writes to the output directory:\n"
      "  replay.json  probes.NAME and overall {n, rmse_c, mae_c, mape_pct, max_error_c, max_error_time_s,\n"
      "               peak_measured_c, peak_measured_time_s, peak_simulated_c, peak_simulated_time_s}; windows[]\n"
      "               (the same per --windows window, with from_s, to_s); log {file, rows, duration_s,\n"
      "               gap_threshold_s}; log_issues[] {kind, line, time_s, detail}; parameters; energy_balance; solver\n"
      "  replay.h5    /time_s, /power_w, /arc_on, /head_mm (rows x 3), /measured/NAME, /simulated/NAME (degC)\n"
      "  probes_replay.png  one panel per probe, measured against simulated\n"
      "replay.json is written last: its presence marks a complete run.");
  command->add_option("scenario", options->scenario, "Scenario YAML with thermal:, process.arc and replay:")
      ->required();
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing)")->required();
  // A list option: A:B,C:D or A:B C:D, joined into the comma-separated form the replay reads.
  auto windows = std::make_shared<std::vector<std::string>>();
  command->add_option("--windows", *windows,
                      "windows A:B,C:D (or A:B C:D) in s from the log's first row, each reported under windows[]")
      ->delimiter(',');
  command->add_option("--parameters", options->parameters,
                      "a fitted file (waam fit thermal -o) whose parameters replace the scenario's");
  command->add_option("--set", options->overrides, "Override a scenario setting, key.path=value (repeatable)");
  command->add_flag("-q,--quiet", options->quiet, "list only the first five log issues on stderr");
  command->add_flag("!--no-images", options->images, "Do not draw probes_replay.png");
  command->callback([options, windows, runner] {
    options->windows.clear();
    for (const std::string& w : *windows) options->windows += (options->windows.empty() ? "" : ",") + w;
    *runner = [options] {
      const analysis::ReplayRunResult r = analysis::RunThermalReplay(*options, std::cerr);
      const nlohmann::json& overall = r.document["overall"];
      std::printf("%zu rows, %.0f s of log, %zu probes: rmse %s degC, max error %s degC; %zu log issues; solved in "
                  "%.1f s -> %s\n",
                  r.model.log.time_s.size(), r.model.log.time_s.back(), r.model.probes.size(),
                  overall["rmse_c"].dump().c_str(), overall["max_error_c"].dump().c_str(),
                  r.model.log.issues.size(), r.simulation.wall_s,
                  (options->out_dir / "replay.json").string().c_str());
      return kExitOk;
    };
  });
  return command;
}

}  // namespace waam::app
