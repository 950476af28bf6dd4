// `waam simulate <scenario.yaml> -o <dir>`: command-line options of the deposition twin.
#include <cstdio>
#include <iostream>
#include <memory>

#include "analysis/simulate_command.h"
#include "app/commands.h"

namespace waam::app {

void AddSimulateCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::SimulateOptions>();
  CLI::App* command = app.add_subcommand(
      "simulate",
      "Plan a scenario (as `waam plan` does), deposit it bead by bead in a sparse voxel twin, and scan the result.\n"
      "The torch path is executed as a robot would run it (blended corners, arc start/stop bead shapes); each bead's\n"
      "parabolic section (width x height from the plan, area 2wh/3) fills the lowest free voxels under it, so\n"
      "overlaps, junction voids and start/stop defects appear in the part. Settings: the scenario's optional\n"
      "`simulation:` section (voxel_mm 0.1-2 mm, default 0.5; blend none|fixed|speed; start_/stop_ lengths and\n"
      "factors; stop_crater lip|lost (where the arc-stop crater's metal goes); start_wetting hot|cold;\n"
      "edge_sag_factor; edge_spread_factor; max_voxels, default 4e8 = about 3.5 GB).\n"
      "Writes to the output directory:\n"
      "  simulate.json      voxel_mm, layers, beads, deposited_volume_mm3, expected_volume_mm3 (sum of bead area x\n"
      "                     length), deviation {min_mm, max_mm, mean_mm, rms_mm} of the part surface from the target\n"
      "                     mesh (+ = excess material), voids {count, volume_mm3, max_length_mm} (enclosed, capped),\n"
      "                     valleys {...} (enclosed in their horizontal cut but open to the top), waviness_mm (largest\n"
      "                     peak-to-valley along the x and y section lines of the top layer), ra_mm (Ding eq. 7),\n"
      "                     top_height {mean_mm, min_mm, max_mm} (Ding Fig. 13, the same columns as ra_mm),\n"
      "                     boundary_lag_mm (interior minus outer-bead mean height); these four are null on\n"
      "                     multi-directional or non-planar parts, not_applicable {measure: reason} says why;\n"
      "                     notes [...] (settings that explain a large deviation), performance, settings\n"
      "  part.stl           surface of the simulated part (binary STL, mm; coplanar voxel faces merged, closed\n"
      "                     and manifold; from a coarser grid past 5 M faces, see stl_voxel_mm)\n"
      "  part.h5            /voxels/{ijk, bead, layer, time_s}, /top_height_mm, /beads; attribute voxel_mm\n"
      "                     (deflate-compressed, chunks of whole rows)\n"
      "  top_height.png, section_xz.png, section_yz.png, deviation_map.png\n"
      "simulate.json is written last: its presence marks a complete run.");
  command->add_option("scenario", options->scenario, "Scenario YAML file")->required();
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing)")->required();
  command->add_option("--set", options->overrides,
                      "Override a scenario setting, key.path=value (repeatable), e.g. --set simulation.voxel_mm=0.25");
  command->add_flag("-q,--quiet", options->quiet, "No progress bar on stderr");
  command->add_flag("!--no-images", options->images, "Do not draw the PNGs");
  command->callback([options, runner] {
    *runner = [options] {
      const twin::TwinMeasures m = analysis::RunSimulate(*options);
      char top[160] = "top-surface measures n/a (see not_applicable)";
      if (m.top_surface_not_applicable.empty()) {
        std::snprintf(top, sizeof(top), "Ra %.3f mm, waviness %.2f mm, boundary lag %.2f mm", m.ra_mm,
                      m.waviness_mm, m.boundary_lag.lag_mm);
      }
      std::printf("deposited %zu layers, %zu beads, %.2f m of bead into %zu voxels of %.2f mm: volume %.0f of %.0f "
                  "mm^3 expected, %s -> %s\n",
                  m.layers, m.beads, m.weld_length_mm / 1000.0, m.voxels, m.voxel_mm, m.deposited_volume_mm3,
                  m.expected_volume_mm3, top, (options->out_dir / "simulate.json").string().c_str());
      return kExitOk;
    };
  });
}

}  // namespace waam::app
