// `waam tune-voids <scenario.yaml> -o <dir>`: command-line options of the junction void-filling tuning.
#include <cstdio>
#include <memory>

#include "analysis/tune_voids_command.h"
#include "app/commands.h"

namespace waam::app {

void AddTuneVoidsCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::TuneVoidsOptions>();
  CLI::App* command = app.add_subcommand(
      "tune-voids",
      "Tune the junction void-filling shift of a rib-web part in the deposition twin (Nguyen 2022 sec. 4.4) instead\n"
      "of welding and milling sacrificial parts. Plans the scenario without void filling, finds its junction classes\n"
      "(ribs and angles between them) and, per class, deposits the first --layers layers on a square crop around one\n"
      "junction: plain contours, the geometric correction (lambda = 1, eq. 4.3), then the shift PP_N* of the sharpest\n"
      "turning point raised by the void length still measured (eq. 4.6) and bisected until the void volume (empty\n"
      "voxels enclosed in horizontal cuts near the junction, below the top layer) is below --threshold-mm3.\n"
      "Writes to the output directory:\n"
      "  tune.json                 per junction class: class, centre_mm, ribs, eta, angles_deg, theta_min_deg,\n"
      "                            plain / geometric / tuned {shift_mm, void_volume_mm3, void_length_mm,\n"
      "                            peak_height_mm}, shift_mm, lambda, void_volume_mm3, peak_height_mm and\n"
      "                            extra_peak_mm (tuned minus plain) of the tuned shift, converged, history\n"
      "  junction_N_plain.png      milled section at mid-height before (grey metal, red empty inside the part)\n"
      "  junction_N_tuned.png      the same with the tuned shift\n"
      "Use the result with path.void_filling: {mode: tuned, tune_file: <dir>/tune.json}. tune.json is written last.");
  command->add_option("scenario", options->scenario, "Scenario YAML file (a rib-web part)")->required();
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing)")->required();
  command->add_option("--set", options->overrides, "Override a scenario setting, key.path=value (repeatable)");
  command->add_option("--layers", options->layers, "Layers deposited per trial (>= 2)")->capture_default_str();
  command->add_option("--threshold-mm3", options->threshold_mm3, "Void volume counted as filled (mm^3)")
      ->capture_default_str();
  command->add_option("--max-trials", options->max_trials, "Simulations per junction class after plain and lambda = 1")
      ->capture_default_str();
  command->add_option("--resolution-mm", options->resolution_mm, "Bracket width at which the search stops (mm)")
      ->capture_default_str();
  command->add_option("--crop-mm", options->crop_mm, "Half-size of the simulated square (mm); 0 = five bead widths")
      ->capture_default_str();
  command->add_option("--training-csv", options->training_csv,
                      "Also write the simulated junctions as an Appendix A1 table (for waam fit void-length)");
  command->add_flag("!--no-images", options->images, "Do not draw the PNGs");
  command->add_flag("-q,--quiet", options->quiet, "No progress bar on stderr");
  command->callback([options, runner] {
    *runner = [options] {
      const analysis::TuneVoidsResult result = analysis::RunTuneVoids(*options);
      for (const analysis::JunctionTuning& j : result.junctions) {
        std::printf("%s: void %.1f mm^3 plain, %.1f with lambda = 1, %.1f with shift %.2f mm (lambda %.2f, %s), "
                    "peak %.2f mm\n",
                    j.junction_class.c_str(), j.plain.void_volume_mm3, j.geometric.void_volume_mm3,
                    j.tuned.void_volume_mm3, j.tuned.shift_mm, j.lambda, j.converged ? "converged" : "not converged",
                    j.tuned.peak_height_mm);
      }
      std::printf("-> %s\n", (options->out_dir / "tune.json").string().c_str());
      return kExitOk;
    };
  });
}

}  // namespace waam::app
