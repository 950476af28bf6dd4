// Speed-height power law v = a h^b (dissertation eq. 6.6): the travel speed that gives a wanted layer height.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/bead/speed_range.h"
#include "models/core/enum_names.h"
#include "models/fit/fit_stats.h"

namespace waam::models {

// v = a * (h / 1 mm)^b with v in mm/min, h in mm; a in mm/min, b dimensionless (negative: higher beads are slower).
struct SpeedHeightParams {
  double a = 0.0;
  double b = 0.0;
};

// How the power law is fitted: residuals of v (nonlinear least squares, the default) or of ln v (the log-log
// straight line that spreadsheet "power trendlines" fit).
enum class PowerLawSpace { kLinear, kLog };
constexpr std::array<EnumName<PowerLawSpace>, 2> EnumNames(PowerLawSpace) {
  return {{{PowerLawSpace::kLinear, "linear"}, {PowerLawSpace::kLog, "log"}}};
}

class SpeedHeightModel {
 public:
  SpeedHeightModel(SpeedHeightParams params, SpeedRange feasible, FitInfo fit = {},
                   PowerLawSpace space = PowerLawSpace::kLinear);

  // Travel speed [mm/min] for layer height `height_mm` (> 0), unclamped.
  double Speed(double height_mm) const;
  // Layer height [mm] the model gives at `speed_mm_per_min` (> 0).
  double Height(double speed_mm_per_min) const;
  // Speed for a wanted height, clamped to the feasible window; reports the clamp and the height obtained.
  // Throws InputError for a non-positive height or b == 0.
  SpeedChoice SpeedForHeight(double height_mm) const;

  const SpeedHeightParams& params() const { return params_; }
  const SpeedRange& feasible() const { return feasible_; }
  const FitInfo& fit() const { return fit_; }
  PowerLawSpace space() const { return space_; }
  // Goodness of fit of ln v (what a log-log "power trendline" reports); n = 0 if the model was not fitted.
  const FitStats& log_stats() const { return log_stats_; }
  void set_log_stats(const FitStats& stats) { log_stats_ = stats; }

  nlohmann::json ToJson() const;
  static SpeedHeightModel FromJson(const nlohmann::json& j, const std::string& where);
  // Loads a file written by `waam fit speed-height`. Throws InputError naming the file.
  static SpeedHeightModel Load(const std::filesystem::path& path);

 private:
  SpeedHeightParams params_;
  SpeedRange feasible_;
  FitInfo fit_;
  PowerLawSpace space_;
  FitStats log_stats_;
};

// Measured layers: travel speed [mm/min] and the layer height [mm] it produced.
struct SpeedHeightSamples {
  std::vector<double> speed_mm_per_min;
  std::vector<double> height_mm;
};

struct SpeedHeightFit {
  SpeedHeightModel model;
  bool ok = false;
  std::string message;
};

// Fits (a, b) with Ceres, starting from the log-log line. fit().stats are of v [mm/min] whichever the space;
// log_stats() are of ln v. The feasible window defaults to the data's speed range. Throws InputError
// (naming `data.file`) for fewer than 3 rows or non-positive values.
SpeedHeightFit FitSpeedHeight(const SpeedHeightSamples& samples, const DataSource& data,
                              PowerLawSpace space = PowerLawSpace::kLinear, const SpeedRange* feasible = nullptr);

}  // namespace waam::models
