// Bead height and width against the interpass temperature where the bead is laid (docs/compensation.md, "Heat into
// shape"): h = h_ref (1 + k_h (T - T_ref)), w = w_ref (1 + k_w (T - T_ref)), or w h held for a volume-conserving bead.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/fit/fit_stats.h"

namespace waam::models {

// The model's parameters. At T = T_ref both factors are exactly 1, so today's bead models (measured at T_ref) are
// reproduced bit for bit.
struct BeadTemperatureParams {
  double reference_c = 20.0;      // T_ref: interpass temperature today's bead models were measured at, degC
  double height_per_k = 0.0;      // k_h: relative change of the bead height per K above T_ref, 1/K
  double width_per_k = 0.0;       // k_w: relative change of the width per K (unused when volume_conserving), 1/K
  bool volume_conserving = false; // w = w_ref / (1 + k_h (T - T_ref)): the bead's cross-section w h stays
  double min_c = 20.0;            // temperature range the model holds for; T is clamped into it, degC
  double max_c = 20.0;
};

class BeadTemperatureModel {
 public:
  // `h_ref_mm`, `w_ref_mm`: the fitted bead at T_ref (mm; 0 when the model was typed in, not fitted).
  // Throws InputError for a factor that is not positive over [min_c, max_c] or min_c > max_c.
  explicit BeadTemperatureModel(BeadTemperatureParams params, double h_ref_mm = 0.0, double w_ref_mm = 0.0,
                                FitInfo fit = {});

  // Factor on the bead height laid on metal at `interpass_c` (degC); 1.0 exactly at T_ref.
  double HeightFactor(double interpass_c) const;
  // Factor on the bead width at `interpass_c` (degC); 1.0 exactly at T_ref.
  double WidthFactor(double interpass_c) const;

  const BeadTemperatureParams& params() const { return params_; }
  double h_ref_mm() const { return h_ref_mm_; }
  double w_ref_mm() const { return w_ref_mm_; }
  const FitInfo& fit() const { return fit_; }
  // Goodness of fit of the width (fit().stats are of the height); n = 0 if the model was not fitted.
  const FitStats& width_stats() const { return width_stats_; }
  void set_width_stats(const FitStats& stats) { width_stats_ = stats; }

  nlohmann::json ToJson() const;
  static BeadTemperatureModel FromJson(const nlohmann::json& j, const std::string& where);
  // Loads a file written by `waam fit bead-temperature`. Throws InputError naming the file.
  static BeadTemperatureModel Load(const std::filesystem::path& path);

 private:
  double Clamp(double interpass_c) const;
  BeadTemperatureParams params_;
  double h_ref_mm_;
  double w_ref_mm_;
  FitInfo fit_;
  FitStats width_stats_;
};

// Measured beads: the interpass temperature where each was laid (degC), its height and width (mm).
struct BeadTemperatureSamples {
  std::vector<double> interpass_c;
  std::vector<double> height_mm;
  std::vector<double> width_mm;
};

struct BeadTemperatureFit {
  BeadTemperatureModel model;
  bool ok = false;
  std::string message;
};

// Fits h_ref, k_h (and w_ref, k_w, or w_ref alone when `volume_conserving`) with Ceres, T_ref = `reference_c`.
// The model's temperature range is the data's (widened to hold T_ref). Throws InputError (naming `data.file`) for
// fewer than 4 rows, fewer than 2 distinct temperatures, or a non-positive height or width.
BeadTemperatureFit FitBeadTemperature(const BeadTemperatureSamples& samples, const DataSource& data,
                                      double reference_c, bool volume_conserving);

}  // namespace waam::models
