// `waam export <scenario.yaml> --format F -o <file>`: command-line options of the program writers.
#include <iostream>
#include <memory>

#include "analysis/export_command.h"
#include "app/commands.h"
#include "app/format_option.h"

namespace waam::app {

void AddExportCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::ExportOptions>();
  auto format = std::make_shared<std::string>("auto");
  CLI::App* command = app.add_subcommand(
      "export",
      "Write the robot program of a scenario in one dialect.\n"
      "Plans the scenario (or reads its program: section), moves the cell along the path as `waam check` does\n"
      "(IK branch, positioner angles) and writes the program: csv (the eight-axis table), fanuc_ls (GP1 + GP2),\n"
      "abb_rapid (.mod: robtargets with quaternions and confdata, ArcLStart/ArcL/ArcLEnd, positioner as external\n"
      "axes), kuka_krl (.src + .dat: E6POS with S/T, E1/E2 positioner, $OUT[1] arc), yaskawa_jbi (.JBI: RB1 + ST1\n"
      "group, C positions in the robot frame with RCONF, EC station pulses, ARCON/ARCOF; needs the station's pulses\n"
      "per degree), gcode (TCP in the part frame, A/C positioner axes, arc on M3 / off M5). auto: from the\n"
      "extension, else the cell preset's dialect (fanuc_ls without a preset).");
  command->add_option("scenario", options->scenario, "Scenario YAML file")->required();
  command->add_option("--format", *format, "Program format: auto | " + EnumNameList<planner::ProgramFormat>(" | "));
  command->add_option("-o,--out", options->out_file, "Program file to write")->required();
  command->add_option("--set", options->overrides, "Override a scenario setting, key.path=value (repeatable)");
  command->add_option("--station-pulses-per-deg", options->station_pulses_per_deg,
                      "yaskawa_jbi: the station's encoder pulses per degree TILT,ROTATION (else the scenario's "
                      "program.yaskawa.station_pulses_per_deg)")
      ->delimiter(',');
  command->add_flag("-q,--quiet", options->quiet, "No progress bar on stderr");
  command->callback([options, format, runner] {
    *runner = [options, format] {
      if (const auto f = ProgramFormatOption(*format)) options->format = f;
      const analysis::ExportResult result = analysis::RunExport(*options);
      std::cout << "wrote " << NameOf(result.format) << ": " << result.points << " points -> "
                << options->out_file.string() << "\n";
      if (result.violations > 0) {
        std::cerr << "waam: warning: the cell check found " << result.violations
                  << " violations along this program (waam check lists them)\n";
      }
      return kExitOk;
    };
  });
}

}  // namespace waam::app
