// `waam import <program> -o <dir>`: command-line options of the program reader.
#include <iostream>
#include <memory>

#include "analysis/import_command.h"
#include "app/commands.h"
#include "app/format_option.h"

namespace waam::app {

void AddImportCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::ImportOptions>();
  auto format = std::make_shared<std::string>("auto");
  CLI::App* command = app.add_subcommand(
      "import",
      "Read a robot program or G-code made elsewhere and write what the twin understood of it.\n"
      "Formats: " + EnumNameList<planner::ProgramFormat>(", ") +
          " (auto: from the extension .csv .ls .mod .src/.dat .jbi .nc/.gcode, or the first lines).\n"
      "Positions are taken in the program's user frame (the scenario's program.frame.user_frame_mm, or the cell's\n"
      "FANUC world frame: arm base lifted to the j2 axis), joint positions through the arm's forward kinematics,\n"
      "external axes / group 2 as the positioner's tilt and rotation; circular moves are cut into chords of\n"
      "cell.checks.step_mm; passes group into layers by their height along the build direction. Instructions the\n"
      "twin does not execute (calls, jumps, weaving, offsets) are listed with their count and first line.\n"
      "Yaskawa INFORM: pulse positions need the controller's pulses per degree (--pulses-per-deg, EC station\n"
      "positions --station-pulses-per-deg, or the scenario's program.yaskawa keys).\n"
      "Writes to the output directory:\n"
      "  plan.json       the fields of `waam plan` plus import {format, motions, motions_by_kind, points,\n"
      "                  warnings [{what, count, first_line}]}\n"
      "  plan.h5         one row per path point, as `waam plan` writes it\n"
      "  layers/*.png    each layer's path\n"
      "plan.json is written last.");
  command->add_option("program", options->program, "Program file")->required()->check(CLI::ExistingFile);
  command->add_option("--format", *format, "Program format: auto | " + EnumNameList<planner::ProgramFormat>(" | "));
  command->add_option("--scenario", options->scenario, "Scenario YAML: the cell, process and program frame");
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing)")->required();
  command->add_option("--set", options->overrides, "Override a scenario setting, key.path=value (repeatable)");
  command->add_option("--pulses-per-deg", options->pulses_per_deg,
                      "Yaskawa INFORM: the arm's encoder pulses per degree S,L,U,R,B,T")
      ->delimiter(',');
  command->add_option("--station-pulses-per-deg", options->station_pulses_per_deg,
                      "Yaskawa INFORM: the station's encoder pulses per degree TILT,ROTATION")
      ->delimiter(',');
  command->add_flag("-q,--quiet", options->quiet, "No progress bar on stderr");
  command->add_flag("!--no-images", options->layer_images, "Do not draw the per-layer PNGs");
  command->callback([options, format, runner] {
    *runner = [options, format] {
      if (const auto f = ProgramFormatOption(*format)) options->format = f;
      const nlohmann::json summary = analysis::RunImport(*options);
      const nlohmann::json& import = summary["import"];
      std::cout << "imported " << import["format"].get<std::string>() << ": " << import["motions"] << " motions, "
                << import["points"] << " points, " << summary["layers"] << " layers, " << summary["passes"]
                << " passes, weld " << summary["weld_length_mm"].get<double>() / 1000.0 << " m, "
                << import["warnings"].size() << " kinds of instruction not executed -> "
                << (options->out_dir / "plan.json").string() << "\n";
      return kExitOk;
    };
  });
}

}  // namespace waam::app
