// `waam place <scenario.yaml> -o <dir>`: command-line options of the layout search.
#include <iostream>
#include <memory>

#include "analysis/place_command.h"
#include "app/commands.h"

namespace waam::app {

void AddPlaceCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::PlaceOptions>();
  CLI::App* command = app.add_subcommand(
      "place",
      "Search the cell layout for one where the scenario's path passes `waam check` with the largest margin.\n"
      "Plans the part once, then checks the path for every layout on the grid of the scenario's place: section\n"
      "(each variable [min, max, step], absolute values of the cell key it names):\n"
      "  part_x_mm, part_y_mm, part_z_mm  cell.part.offset_mm: where the part stands on the plate (z: a riser)\n"
      "  part_yaw_deg                     cell.part.yaw_deg: the part's turn on the plate\n"
      "  table_rotation_deg               cell.positioner.rotation_deg: the table's home rotation\n"
      "  positioner_yaw_deg               cell.positioner.yaw_deg\n"
      "  robot_x_mm, robot_y_mm           cell.robot.base_mm: where the arm stands\n"
      "Without a place: section it searches the part's offset (-40..40 mm, step 20) and yaw (0..315 deg, step 45).\n"
      "Coarse to fine: every layout is checked on place.coarse_layers layers (24) at place.coarse_step_mm (5 mm),\n"
      "in parallel; the best place.finalists (4) then on the whole path, until one passes. Margin: the smallest of\n"
      "(arm joint margin - cell.checks.joint_margin_deg) / 10 deg, (|J5| - singularity_deg) / 10 deg, clearance / 10 mm.\n"
      "Writes to the output directory:\n"
      "  place.json        feasible, best (layout, overrides, margins, worst violation), every layout tried\n"
      "  scenario.yaml     the scenario with the best layout (base_dir points back at its files): waam check it\n"
      "  place_margin.png  the margin over the first two searched variables, the answer circled\n"
      "Exit code 0 when a layout passes the whole check, 3 when none does (place.json then names the nearest miss).");
  command->add_option("scenario", options->scenario, "Scenario YAML file")->required();
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing)")->required();
  command->add_option("--set", options->overrides,
                      "Override a scenario setting, key.path=value (repeatable), e.g. --set place.part_yaw_deg=[0,90,45]");
  command->add_flag("-q,--quiet", options->quiet, "No progress bar on stderr");
  command->add_flag("!--no-images", options->images, "Do not draw place_margin.png");
  command->add_flag("--exhaustive", options->exhaustive,
                    "No pruning: every coarse check and every resolved motion checked whole; the same answer, slower");
  command->callback([options, runner] {
    *runner = [options] {
      const analysis::PlaceResult result = analysis::RunPlace(*options);
      const analysis::LayoutScore& s = result.best_score;
      std::cout << (result.feasible ? "feasible" : "NO LAYOUT PASSES") << ": " << result.layouts.size()
                << " layouts on the coarse pass (" << result.coarse_bounded << " pruned, " << result.coarse_s << " s), "
                << result.full.size()
                << " on the whole path (" << result.full_s << " s); best:";
      for (int v = 0; v < analysis::kPlaceVars; ++v) {
        if (result.values[v].size() > 1) {
          std::cout << " " << analysis::PlaceVariableName(v) << "=" << result.layouts[result.best][v];
        }
      }
      std::cout << ", margin " << s.margin << " (joint " << s.min_joint_margin_deg << " deg, j5 " << s.min_j5_deg
                << " deg, clearance " << s.min_clearance_mm << " mm)";
      if (!result.feasible) {
        std::cout << "; nearest miss: " << s.violating_samples << " violating samples, worst " << s.worst << " "
                  << s.worst_unit << " = " << s.worst_value << " at layer " << s.worst_layer;
      }
      std::cout << " -> " << (options->out_dir / "place.json").string() << "\n";
      return result.feasible ? kExitOk : kExitViolations;
    };
  });
}

}  // namespace waam::app
