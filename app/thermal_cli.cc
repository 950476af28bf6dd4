// `waam thermal <scenario.yaml> -o <dir>`: command-line options of the thermal model's run along the build timeline.
#include <cstdio>
#include <memory>

#include "analysis/thermal_command.h"
#include "app/commands.h"

namespace waam::app {

void AddThermalCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::ThermalOptions>();
  CLI::App* command = app.add_subcommand(
      "thermal",
      "Plan a scenario (or read its program:), build its timeline (arc on, arc start/end, travel, positioner moves,\n"
      "waits) and run the transient thermal model of deposit and plate along it: the arc heats each bead as it is\n"
      "laid (heat = process.arc efficiency x power), travel and waits cool the part. With process.interpass.max_c the\n"
      "build waits before each layer until the temperature at `at` (next_start: the metal under the next layer's\n"
      "first arc start; top_max: the hottest point of the layer below; {probe: NAME}) is at most max_c; the timeline\n"
      "then includes those waits. Keys (docs/THERMAL.md): thermal.material, thermal.substrate {size_mm, centre_mm,\n"
      "material}, thermal.cell_mm, ambient_c, initial_c, convection_w_m2k, emissivity, table {conductance_w_m2k,\n"
      "temperature_c}, sample_s, probes {NAME: [x, y, z] mm, part frame}; process.arc {power_w | voltage_v +\n"
      "current_a, efficiency (default 0.84)}; process.interpass {max_c, at, min_layer_time_s}.\n"
      "Writes to the output directory:\n"
      "  thermal.json   timeline {total_s, arc_on_s, travel_s, wait_s, layers[]}; layers[] {layer, start_s, end_s,\n"
      "                 interpass_c, peak_c, wait_s, interpass_reached}; probes.NAME {position_mm, max_c,\n"
      "                 time_of_max_s}; energy_balance {arc_energy_j, efficiency, heat_input_j, stored_j, lost_j,\n"
      "                 convection_j, radiation_j, table_j, relative_error}; solver {cells, active_cells, steps,\n"
      "                 iterations, wall_s}; build_time_s, total_wait_s, max_interpass_c, peak_c\n"
      "  thermal.h5     /probes/time_s, /probes/NAME (degC); /layers/*; /timeline/*; /fields/layer_NNNN (the\n"
      "                 temperature at each layer's end, nz x ny x nx degC, attributes origin_mm, cell_mm, dims)\n"
      "  interpass.png, probes.png, maps/layer_NNNN.png (vertical section of the temperature at each layer's end)\n"
      "thermal.json is written last: its presence marks a complete run.");
  command->add_option("scenario", options->scenario, "Scenario YAML file with a thermal: section (required)");
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing) (required)");
  command->add_option("--set", options->overrides,
                      "Override a scenario setting, key.path=value (repeatable), e.g. --set process.interpass.max_c=150");
  command->add_flag("-q,--quiet", options->quiet, "No progress bar on stderr");
  command->add_flag("!--no-images", options->images, "Do not draw the PNGs");
  CLI::App* replay = AddThermalReplayCommand(*command, runner);
  command->callback([command, replay, options, runner] {
    if (command->got_subcommand(replay)) return;  // `waam thermal replay` set the runner
    if (options->scenario.empty()) throw CLI::RequiredError("scenario");
    if (options->out_dir.empty()) throw CLI::RequiredError("--out");
    *runner = [options] {
      const analysis::ThermalRunResult r = analysis::RunThermal(*options);
      double waits = 0.0, peak = 0.0;
      for (const analysis::ThermalLayer& l : r.layers) {
        waits += l.wait_s;
        if (l.peak_c > peak) peak = l.peak_c;
      }
      std::printf("%zu layers: build %.0f s (arc on %.0f s, travel %.0f s, waits %.0f s of which interpass %.0f s), "
                  "peak %.0f degC; energy balance error %.2g; %zu cells, %zu steps in %.1f s -> %s\n",
                  r.layers.size(), r.timeline.total_s, r.timeline.arc_on_s, r.timeline.travel_s, r.timeline.wait_s,
                  waits, peak, r.energy.RelativeError(), r.stats.cells, r.stats.steps, r.wall_s,
                  (options->out_dir / "thermal.json").string().c_str());
      return kExitOk;
    };
  });
}

}  // namespace waam::app
