// `waam plan <scenario.yaml> -o <dir>`: command-line options of the planner.
#include <iostream>
#include <memory>

#include "analysis/plan_command.h"
#include "app/commands.h"

namespace waam::app {

void AddPlanCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::PlanOptions>();
  CLI::App* command = app.add_subcommand(
      "plan",
      "Slice a part and plan its weld path layer by layer.\n"
      "Reads a scenario YAML (part mesh or generator, layer height, path pattern " +
          EnumNameList<planner::Pattern>("|") +
          ",\nbead width, overlap model, void filling, process speeds; slicing.type skeleton for bent thin-walled\n"
          "tubes plans spiral or contour only) and writes to the output directory:\n"
      "  plan.json       layers, passes (arc starts), passes_per_layer, path_elements, weld_length_mm,\n"
      "                  travel_length_mm, estimated_time_s (= timeline.total_s), timeline (arc on, travel, waits\n"
      "                  per layer: docs/TIMELINE.md), uncovered (share of the slice no bead covers), the mesh report\n"
      "  plan.h5         /layers/layer_NNNN: one row per path point (x, y, z mm, tool direction, bead width and\n"
      "                  height mm, travel speed mm/min, weld 0/1, layer)\n"
      "  layers/*.png    the slice, the path in sequence colours, arc starts and stops, seen along the layer's\n"
      "                  build direction (a cone or cylinder layer: its path from +z, no slice)\n"
      "plan.json is written last: its presence marks a complete run.");
  command->add_option("scenario", options->scenario, "Scenario YAML file")->required();
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing)")->required();
  command->add_option("--set", options->overrides,
                      "Override a scenario setting, key.path=value (repeatable), e.g. --set path.pattern=hybrid");
  command->add_flag("-q,--quiet", options->quiet, "No progress bar on stderr");
  command->add_flag("!--no-images", options->layer_images, "Do not draw the per-layer PNGs");
  command->callback([options, runner] {
    *runner = [options] {
      const planner::PlanResult result = analysis::RunPlan(*options);
      std::cout << "planned " << result.stats.layers << " layers, " << result.stats.passes << " passes, "
                << result.stats.path_elements << " path elements, weld " << result.stats.weld_length_mm / 1000.0
                << " m, estimated " << result.stats.estimated_time_s / 60.0 << " min -> "
                << (options->out_dir / "plan.json").string() << "\n";
      return kExitOk;
    };
  });
}

}  // namespace waam::app
