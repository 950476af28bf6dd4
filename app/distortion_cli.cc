// `waam deviation` and `waam compensate`: command-line options of the scan comparison and the compensation loop.
#include <cstdio>
#include <memory>

#include "analysis/distortion_command.h"
#include "app/commands.h"

namespace waam::app {

void AddDeviationCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::DeviationOptions>();
  CLI::App* command = app.add_subcommand(
      "deviation",
      "Compare a scan of a part with its target, as a GOM-style scan-to-CAD check (003 sec. 6.4.2). Both are in the\n"
      "part frame in mm (align the scan first). The scan is a point cloud: .ply (ascii or binary_little_endian,\n"
      "vertex x y z), .xyz (x y z per line) or .stl (its surface sampled every 0.5 mm, each point weighted by the\n"
      "area it stands for, without the face the part stands on: facets facing down in the lowest plane).\n"
      "Writes to the output directory:\n"
      "  deviation.json     min_mm, max_mm, mean_mm, rms_mm, max_abs_mm of the signed deviation (+ = material\n"
      "                     outside the target), axis {max_deviation_mm, samples: s_mm, center_mm, deviation_mm}\n"
      "                     (central axis of the target by adaptive slicing, 003 sec. 6.3.1, and the scan's section\n"
      "                     centroids there), sections bottom/middle/top {target, scan: d_min_mm, d_max_mm,\n"
      "                     ovality_pct} and ovality_pct (top section, eq. 6.5: 200 (dmax - dmin) / (dmax + dmin)),\n"
      "                     weighting (\"area\" for an STL scan, \"point\" otherwise), bottom_excluded {facets,\n"
      "                     area_mm2}\n"
      "  deviation.ply      the scan points with a deviation_mm property\n"
      "  deviation_map.png  front and side views coloured by deviation");
  command->add_option("target", options->target, "Target part, STL (mm)")->required();
  command->add_option("scan", options->scan, "Scan point cloud: .ply, .xyz or .stl (mm)")->required();
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing)")->required();
  command->add_option("--axis-step-mm", options->axis_step_mm, "Central-axis station spacing, mm (default 2)");
  command->add_flag("--keep-bottom", options->keep_bottom,
                    "An STL scan: keep the facets the part stands on (a scan of the part off its plate)");
  command->add_flag("!--no-images", options->images, "Do not draw the PNG");
  command->callback([options, runner] {
    *runner = [options] {
      const nlohmann::json j = analysis::RunDeviation(*options);
      std::printf("deviation %.3f .. %.3f mm (rms %.3f mm) over %zu points, central axis %.3f mm, ovality %.2f %% -> %s\n",
                  j["min_mm"].get<double>(), j["max_mm"].get<double>(), j["rms_mm"].get<double>(),
                  j["points"].get<std::size_t>(), j["axis"]["max_deviation_mm"].get<double>(),
                  j["ovality_pct"].get<double>(), (options->out_dir / "deviation.json").string().c_str());
      return kExitOk;
    };
  });
}

void AddCompensateCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::CompensateOptions>();
  CLI::App* command = app.add_subcommand(
      "compensate",
      "Offline shrinkage and distortion compensation (003 sec. 6.5.2) tuned in the twin: plan the scenario, deposit\n"
      "it in the voxel twin, let it shrink and distort (inherent-strain model, models/data/distortion.json), scan it,\n"
      "then move every reference point of the tool path (2 mm apart) against the deviation measured around it,\n"
      "r*_i = r_i - S_i, in each layer's plane: S_i is the scan's section-centre offset from the reference's central\n"
      "axis plus the move of its section outline (72 directions), plus the closest-point remainder. The build-direction\n"
      "shrinkage is not corrected by the path: the top rim (2 bead heights + the shortening the scan shows) is left\n"
      "out of the measures. Build again until max |deviation| < tolerance (default: the maximum side-wall waviness\n"
      "of the simulated part, W_t in 4 mm cells, 99th percentile: 003 stops 'within the maximum waviness')\n"
      "or --max-iter compensations are done. A loop whose deviation stops shrinking says so and stops (status\n"
      "diverging). --scan replaces the first simulated part with a real scan (aligned, part frame, mm).\n"
      "Writes: compensate.json (tolerance_mm, waviness_mm, waviness_median_mm, converged, status, message,\n"
      "iterations[]: max_abs_deviation_mm,\n"
      "rms_deviation_mm, p99_abs_deviation_mm, axis_deviation_mm, ovality_pct (eq. 6.5, highest complete section),\n"
      "max_correction_mm, top_band_mm, twin_correction_error_mm (twin-only check, never used), distortion solve\n"
      "size and time), compensated_path.h5 (plan.h5 layout), program/ (program.ls, program.csv, check.json of the\n"
      "compensated path), scan_before.ply, scan_after.ply, deviation_before.png, deviation_after.png.\n"
      "Exit code 0 also when the loop did not converge (see `converged`).");
  command->add_option("scenario", options->scenario, "Scenario YAML file")->required();
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing)")->required();
  command->add_option("--max-iter", options->max_iterations, "Compensated builds after the first, 0-20 (default 3)")
      ->check(CLI::Range(0, 20));
  command->add_option("--tol-mm", options->tolerance_mm, "Tolerance on max |deviation|, mm (default: maximum waviness)")
      ->check(CLI::Range(0.0, 1000.0));
  command->add_option("--scan", options->first_scan, "Real scan of the first part (.ply, .xyz or .stl, mm; an STL as in `waam deviation`)");
  command->add_option("--model", options->model, "Distortion model JSON (default models/data/distortion.json)");
  command->add_option("--mode", options->mode, "fe (inherent-strain FE) or reduced (layer shrinkage + axis bending)");
  command->add_option("--element-mm", options->element_mm, "FE element edge, mm (default 2)");
  command->add_option("--groups", options->groups, "Layer groups activated in turn (default 4)");
  command->add_option("--correction", options->correction,
                      "axis (default: bend the central axis back by the scan's section-centre offset, then correct the\n"
                      "cross sections point by point) or points (per-point closest-point deviation only)")
      ->check(CLI::IsMember({"axis", "points"}));
  command->add_option("--set", options->overrides, "Override a scenario setting, key.path=value (repeatable)");
  command->add_option("--debug-level", options->debug_level,
                      "Diagnostics on stderr: 0 none (default), 1 waviness, top band and the twin's correction error "
                      "every tenth layer, 2 every layer")
      ->check(CLI::Range(0, 2));
  command->add_flag("-q,--quiet", options->quiet, "No progress bar on stderr");
  command->add_flag("!--no-images", options->images, "Do not draw the PNGs");
  command->add_flag("!--no-program", options->program, "Do not write the robot program (no cell check)");
  command->callback([options, runner] {
    *runner = [options] {
      const twin::CompensationResult r = analysis::RunCompensate(*options);
      std::printf("%s -> %s\n", r.message.c_str(), (options->out_dir / "compensate.json").string().c_str());
      return kExitOk;
    };
  });
}

}  // namespace waam::app
