// `waam fit`: command-line options for fitting a process model to a CSV table (or the distortion model to a scan).
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/fit_command.h"
#include "app/commands.h"
#include "models/core/csv.h"
#include "models/core/enum_names.h"
#include "models/core/error.h"

namespace waam::app {
namespace {

// `waam fit --help`: the models, their formulas and default CSV columns.
constexpr const char* kFitHelp =
    "Fit a process model to measured data (Ceres least squares) and write it as a model JSON file.\n"
    "Prints params, r2, rmse = sqrt(SSE/n), rmse_dof = sqrt(SSE/(n - number of parameters)) and n.\n"
    "Models (default CSV columns in brackets; '#' lines in the CSV are kept as provenance):\n"
    "  csw           w = m v^(-1/3) + p/r + t (Dai et al. 2020): bead width w [mm] from travel speed v [mm/min]\n"
    "                and path curvature radius r [mm] ('inf' = straight)\n"
    "                [speed=travel_speed_mm_per_min radius=curvature_radius_mm width=width_mm]\n"
    "  speed-height  v = a h^b (Nguyen 2022 eq. 6.6): travel speed v [mm/min] for layer height h [mm]\n"
    "                [speed=travel_speed_mm_per_min height=height_mm]\n"
    "  width-height  w = sum c_k h^k, --degree (4 in Nguyen eq. 6.7): bead width w [mm] from height h [mm]\n"
    "                [height=height_mm width=width_mm speed=travel_speed_mm_per_min (only with --speed-range)]\n"
    "  bead-temperature  h = h_ref (1 + k_h (T - T_ref)), w = w_ref (1 + k_w (T - T_ref)) (w = w_ref / (1 + k_h\n"
    "                (T - T_ref)) with --volume-conserving): bead height h and width w [mm] against the interpass\n"
    "                temperature T [degC] where the bead was laid; T_ref = --reference-c, the temperature today's\n"
    "                bead models were measured at (docs/compensation.md) [temperature=interpass_c height=height_mm\n"
    "                width=width_mm]\n"
    "  void-length   junction void length L [mm] from eta (turning points) and the four angles theta1..4 [deg]\n"
    "                (Nguyen ch. 4.4, Appendix A1): a tanh network (--hidden, L2/Bayesian penalty, seeded\n"
    "                restarts, averaged) or the baseline L = a + b (1/sin(theta_min/2) - 1); both are cross-validated\n"
    "                (--folds or --loo) and the Table 11 junctions (--holdout) predicted from the other rows\n"
    "                [eta=eta theta1=theta1_deg .. theta4=theta4_deg void=void_length_mm label=group]\n"
    "  distortion    inherent-strain distortion parameters (models/data/distortion.json format) from a scan of a\n"
    "                built part: `waam fit distortion <scan> --scenario <part.yaml> -o <out.json>`. The data is the\n"
    "                scan, not a CSV: .ply (vertex x y z), .xyz (x y z per line) or .stl (sampled every 0.5 mm), in\n"
    "                the part frame in mm (aligned; substrate top z = 0). The scenario is planned and deposited in\n"
    "                the voxel twin as built; Ceres moves the --free parameters (from --start) until the distorted\n"
    "                twin surface passes through the scan (residual: each scan point pulled back through the twin's\n"
    "                displacement field onto the deposit's exposed voxel faces, its distance to the face's plane\n"
    "                [mm], Huber loss 1 mm). Prints the fitted values, rms residual at the start and fitted [mm], Ceres\n"
    "                iterations; a fit Ceres did not converge is not written (exit 2). The\n"
    "                JSON gets a \"fit\" record (scan, scenario, free, start, rms_start_mm, rms_mm, solver).\n"
    "                A twin scan at known parameters: `waam compensate <part.yaml> --model known.json --max-iter 0\n"
    "                --no-program -o dir` writes dir/scan_before.ply (side faces, top end face left out).\n"
    "  thermal       the thermal model's uncertain parameters from a build's process log (docs/REPLAY.md):\n"
    "                `waam fit thermal <scenario.yaml> --free efficiency,convection,contact[,emissivity] --window\n"
    "                START:END -o fitted.json`. The data is the scenario (its replay: section names the log). Ceres\n"
    "                moves the --free parameters (default efficiency,convection,contact; from the scenario or --start,\n"
    "                a fitted file) until the replayed thermocouples match the measured ones inside --window (s from\n"
    "                the log's first row); the rest of the log is predicted. Writes parameters, set (the --set lines\n"
    "                for any scenario), start, fitted, window and held_out {probes.NAME, overall: rmse_c, mae_c,\n"
    "                mape_pct, max_error_c, peaks}, solver, time_s. `waam thermal replay --parameters fitted.json`\n"
    "                replays with them. A fit Ceres did not converge is not written (exit 2).\n"
    "Exit code 2 for bad input or a fit the solver could not make usable (the message says why).";

// The options taken as names (closed sets, parsed into their enums when the command runs) or reshaped after parsing.
struct FitNames {
  std::string model;
  std::string space;
  std::string kind;
  std::string angle_order;
  std::vector<double> speed_range;
  std::string jacobian_cell = "auto";
};

// The options of `waam fit void-length`.
void AddVoidLengthOptions(CLI::App* fit, analysis::FitOptions* options, FitNames* names) {
  fit->add_option("--kind", names->kind, "void-length model written: network | baseline")->capture_default_str();
  fit->add_option("--hidden", options->hidden, "void-length hidden layer sizes, e.g. 7,7")->delimiter(',');
  fit->add_option("--l2", options->l2, "void-length L2 penalty weight on normalised weights (start value)")
      ->capture_default_str();
  fit->add_flag("!--no-bayesian", options->bayesian, "keep --l2 fixed instead of the Bayesian evidence update");
  fit->add_option("--restarts", options->restarts, "void-length seeded random restarts")->capture_default_str();
  fit->add_flag("!--best-only", options->ensemble,
                "void-length: keep the restart with the lowest training objective instead of averaging all restarts");
  fit->add_option("--seed", options->seed, "seed for restarts and fold assignment")->capture_default_str();
  fit->add_option("--folds", options->folds, "k of the k-fold cross-validation")->capture_default_str();
  fit->add_flag("--loo", options->leave_one_out, "leave-one-out cross-validation instead of k-fold");
  fit->add_option("--angle-order", names->angle_order,
                  "void-length: as_given (order round the junction, as printed) | sorted_descending (also: sorted);\n"
                  "the model file's params.angle_order")
      ->capture_default_str();
  fit->add_option("--holdout", options->holdout, "labels predicted from a model trained on the other rows")
      ->delimiter(',');
}

// The options of `waam fit distortion` and `waam fit thermal` (a scan or a replay, not a CSV); returns --free.
CLI::Option* AddScanOptions(CLI::App* fit, analysis::FitOptions* options, FitNames* names) {
  fit->add_option("--scenario", options->scenario, "distortion: scenario YAML the scanned part was built from");
  fit->add_option("--set", options->overrides, "distortion: override a scenario setting, key.path=value (repeatable)");
  fit->add_option("--start", options->start,
                  "distortion: start parameters, a distortion model JSON (default models/data/distortion.json); the\n"
                  "parameters not in --free keep its values; thermal: a fitted file to start from");
  fit->add_option("--window", options->window, "thermal: START:END, the part of the log fitted, s from its first row");
  fit->add_option("--coarse-cell", options->coarse_cell_mm,
                  "thermal: grid spacing of a first fit whose answer starts the fit on the scenario's grid, mm, "
                  "e.g. twice thermal.cell_mm (default 0: one fit on the scenario's grid)");
  fit->add_option("--jacobian-cell", names->jacobian_cell,
                  "thermal: grid spacing the Jacobians (and the 1 sd) are differenced on, mm: the residuals, the cost\n"
                  "and every step's test stay on the scenario's grid; 0: every Jacobian on the scenario's grid;\n"
                  "auto: 1.5 times thermal.cell_mm where that grid holds the bead's width and the plate's thickness\n"
                  "in two cells or more, else 0")
      ->type_name("auto|MM")
      ->capture_default_str();
  fit->add_option("--prior", options->prior_weight,
                  "thermal: weak prior toward the start values, degC: one residual W (value - start) / scale per free\n"
                  "parameter (scales: efficiency 1, convection 10, contact 100, emissivity 1; default 0: none)");
  CLI::Option* free = fit->add_option("--free", options->free,
                  "distortion: parameters fitted, any of strain [1], vertical_ratio [1], heat_exponent [1],\n"
                  "substrate_stiffness_n_mm3 [N/mm^3] (fe mode only); thermal: any of efficiency, convection,\n"
                  "contact, emissivity (default efficiency,convection,contact)")
      ->delimiter(',')
      ->default_str("strain,vertical_ratio");
  fit->add_option("--mode", options->mode, "distortion: fe | reduced (default: the --start file's mode)");
  fit->add_option("--element-mm", options->element_mm, "distortion: fe element edge, mm")->capture_default_str();
  fit->add_option("--groups", options->groups, "distortion: fe layer groups activated in turn")->capture_default_str();
  fit->add_option("--max-points", options->max_points, "distortion: scan points used (every k-th point)")
      ->capture_default_str();
  fit->add_option("--max-iter", options->max_iterations,
                  "distortion: Ceres iterations (1-1000); a fit that has not converged by then is not written")
      ->capture_default_str();
  return free;
}

// The names of --space, --kind and --angle-order parsed into `options`. Throws InputError naming the option.
void ParseFitNames(const FitNames& names, analysis::FitOptions* options) {
  const std::optional<models::PowerLawSpace> space = ParseEnum<models::PowerLawSpace>(names.space);
  WAAM_THROW_UNLESS(space, "--space '" << names.space << "': must be linear or log");
  options->space = *space;
  const std::optional<analysis::VoidModelKind> kind = ParseEnum<analysis::VoidModelKind>(names.kind);
  WAAM_THROW_UNLESS(kind, "--kind '" << names.kind << "': must be network or baseline");
  options->kind = *kind;
  // `sorted` is the spelling the option had before it took the model file's name.
  const std::optional<models::AngleOrder> order = names.angle_order == "sorted"
                                                      ? models::AngleOrder::kSortedDescending
                                                      : ParseEnum<models::AngleOrder>(names.angle_order);
  WAAM_THROW_UNLESS(order, "--angle-order '" << names.angle_order << "': must be "
                                             << EnumNameList<models::AngleOrder>(" or ") << " (or sorted)");
  options->angle_order = *order;
  if (names.jacobian_cell == "auto") {
    options->jacobian_cell_mm = analysis::kAutoJacobianCell;
  } else {
    double mm = -1.0;
    WAAM_THROW_UNLESS(ParseCsvNumber(names.jacobian_cell, false, &mm) && mm >= 0.0,
                      "--jacobian-cell '" << names.jacobian_cell << "': must be auto, 0 (the scenario's grid) or a "
                                             "grid spacing in mm");
    options->jacobian_cell_mm = mm;
  }
}

}  // namespace

void AddFitCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::FitOptions>();
  auto names = std::make_shared<FitNames>();
  names->space = NameOf(options->space);
  names->kind = NameOf(options->kind);
  names->angle_order = NameOf(options->angle_order);
  CLI::App* fit = app.add_subcommand("fit", kFitHelp);
  std::vector<std::string> models;
  for (const EnumName<analysis::FitModel>& entry : EnumNames(analysis::FitModel{})) models.emplace_back(entry.name);
  fit->add_option("model", names->model, EnumNameList<analysis::FitModel>(" | "))
      ->required()
      ->check(CLI::IsMember(models));
  fit->add_option("data", options->data, "CSV file with a header row (distortion: the scan, .ply, .xyz or .stl)")
      ->required();
  fit->add_option("-o,--output", options->output, "model JSON to write (atomically)")->required();
  fit->add_option("--columns", options->columns,
                  "role=column overrides, e.g. --columns speed=v,width=w_mm (roles listed above)")
      ->delimiter(',');
  fit->add_option("--speed-range", names->speed_range,
                  "feasible travel-speed window MIN MAX or MIN,MAX [mm/min]: rows outside it are left out of the fit (and "
                  "listed), and the inverse models clamp to it; default: all rows, window = the data's speed range")
      ->expected(2)
      ->delimiter(',');
  fit->add_option("--degree", options->degree, "width-height polynomial degree (1-8)")->capture_default_str();
  fit->add_option("--space", names->space, "speed-height residuals in v (linear) or ln v (log)")
      ->capture_default_str();
  fit->add_option("--reference-c", options->reference_c,
                  "bead-temperature: T_ref, the interpass temperature the bead models were measured at [degC]")
      ->capture_default_str();
  fit->add_flag("--volume-conserving", options->volume_conserving,
                "bead-temperature: the width follows the height so that w h stays (k_w not fitted)");
  AddVoidLengthOptions(fit, options.get(), names.get());
  CLI::Option* free = AddScanOptions(fit, options.get(), names.get());
  fit->add_flag("-q,--quiet", options->quiet, "no progress bar and no line per iteration (fit thermal) on stderr");
  fit->callback([runner, options, names, free] {
    options->model = analysis::ParseFitModel(names->model);  // a name IsMember let through
    if (options->model == analysis::FitModel::kThermal && free->count() == 0) {
      options->free = {"efficiency", "convection", "contact"};
    }
    if (names->speed_range.size() == 2) {
      options->speed_range = std::make_pair(names->speed_range[0], names->speed_range[1]);
    }
    *runner = [options, names] {
      ParseFitNames(*names, options.get());
      const analysis::FitOutcome outcome = analysis::RunFit(*options, std::cout);
      if (!outcome.ok) {
        std::cerr << "waam: error: fit of " << options->data.string() << " failed: " << outcome.message << "\n";
        return kExitBadInput;
      }
      return kExitOk;
    };
  });
}

}  // namespace waam::app
