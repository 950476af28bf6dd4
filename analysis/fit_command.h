// `waam fit`: fits one process model to a CSV table, prints a summary and writes the model JSON atomically.
#pragma once

#include <array>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/bead/speed_height_model.h"
#include "models/core/enum_names.h"
#include "models/voids/void_length_network.h"

namespace waam::analysis {

// The models `waam fit` fits.
enum class FitModel { kCsw, kSpeedHeight, kWidthHeight, kBeadTemperature, kVoidLength, kDistortion, kThermal };
constexpr std::array<EnumName<FitModel>, 7> EnumNames(FitModel) {
  return {{{FitModel::kCsw, "csw"},
           {FitModel::kSpeedHeight, "speed-height"},
           {FitModel::kWidthHeight, "width-height"},
           {FitModel::kBeadTemperature, "bead-temperature"},
           {FitModel::kVoidLength, "void-length"},
           {FitModel::kDistortion, "distortion"},
           {FitModel::kThermal, "thermal"}}};
}
// The model named `name`; throws InputError "unknown model 'name': must be one of csw, ..." for another name.
FitModel ParseFitModel(const std::string& name);

// The void-length model `waam fit void-length` writes (both are cross-validated).
enum class VoidModelKind { kNetwork, kBaseline };
constexpr std::array<EnumName<VoidModelKind>, 2> EnumNames(VoidModelKind) {
  return {{{VoidModelKind::kNetwork, "network"}, {VoidModelKind::kBaseline, "baseline"}}};
}

// FitOptions::jacobian_cell_mm for `--jacobian-cell auto`.
inline constexpr double kAutoJacobianCell = -1.0;

// Everything `waam fit` accepts; the CLI fills it, tests build it directly.
struct FitOptions {
  FitModel model = FitModel::kCsw;
  std::filesystem::path data;             // CSV input (distortion: the scan, .ply, .xyz or .stl, part frame, mm)
  std::filesystem::path output;           // model JSON output
  std::vector<std::string> columns;       // "role=column" overrides of the default column names
  std::optional<std::pair<double, double>> speed_range;  // feasible travel speeds [mm/min]; default: the data's
  int degree = 4;                         // width-height polynomial degree
  models::PowerLawSpace space = models::PowerLawSpace::kLinear;  // speed-height residuals in v or ln v
  // bead-temperature
  double reference_c = 20.0;              // T_ref: interpass temperature the bead models were measured at, degC
  bool volume_conserving = false;         // width from w h = const instead of its own slope
  // void-length
  VoidModelKind kind = VoidModelKind::kNetwork;  // the model written (both are cross-validated)
  std::vector<int> hidden = {7, 7};
  double l2 = 0.01;
  bool bayesian = true;
  int restarts = 5;
  bool ensemble = true;                   // average the restarts (false: keep the best)
  unsigned long long seed = 1;
  int folds = 5;
  bool leave_one_out = false;
  models::AngleOrder angle_order = models::AngleOrder::kAsGiven;
  std::vector<std::string> holdout = {"F7", "H3", "H15"};  // dissertation Table 11; empty = skip
  // distortion: the scan of a part built from `scenario` is matched by the distorted twin of that build
  std::filesystem::path scenario;         // scenario YAML of the nominal build the scan came from
  std::vector<std::string> overrides;     // --set key.path=value on the scenario
  std::filesystem::path start;            // start parameters (distortion model JSON); empty = models/data/distortion.json
  std::vector<std::string> free = {"strain", "vertical_ratio"};  // fitted; the others stay at the start values
  std::string mode;                       // fe | reduced; empty = the start file's mode
  double element_mm = 2.0;                // fe element edge, mm
  int groups = 4;                         // fe activation groups
  std::size_t max_points = 3000;          // scan points used (every k-th), >= 10
  int max_iterations = 30;                // Ceres iterations, 1-1000
  // thermal: `data` is the scenario (with replay:), `free` of efficiency, convection, contact, emissivity, `start`
  // an optional fitted file to start from, `window` the part of the log fitted
  std::string window;                     // "START:END", s from the log's first row
  double coarse_cell_mm = 0.0;            // grid of a coarse first stage, mm; 0 (or <= thermal.cell_mm): none
  // grid the Jacobians are differenced on, mm; 0: thermal.cell_mm's; kAutoJacobianCell (the default): 1.5 times
  // thermal.cell_mm where that grid holds the bead's width and the plate's thickness in two cells, else 0
  double jacobian_cell_mm = kAutoJacobianCell;
  double prior_weight = 0.0;              // --prior W: pull toward the start values, degC per scaled unit; 0: none
  bool quiet = false;                     // no progress bar
};

// The outcome: ok = the solver's answer is usable and the file was written; otherwise `message` says why.
struct FitOutcome {
  bool ok = false;
  std::string message;
  nlohmann::json model;  // what was written (or would have been)
};

// Runs the fit described by `options`, prints a readable summary to `out` and writes options.output atomically
// (only when the fit is usable). Throws InputError for bad options or a bad CSV (one line naming file, line,
// column).
FitOutcome RunFit(const FitOptions& options, std::ostream& out);

// The role=default-column table of `model` (for --help and errors).
std::vector<std::pair<std::string, std::string>> DefaultFitColumns(FitModel model);

}  // namespace waam::analysis
