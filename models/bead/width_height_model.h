// Width-height polynomial w = sum c_k h^k (dissertation eq. 6.7, degree 4 there): the bead width a layer height brings.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/bead/speed_height_model.h"
#include "models/fit/fit_stats.h"

namespace waam::models {

class WidthHeightModel {
 public:
  // `coefficients[k]` multiplies (h / 1 mm)^k [mm]; `height_range_mm` = {min, max} of the data it was fitted on.
  WidthHeightModel(std::vector<double> coefficients, double min_height_mm, double max_height_mm, FitInfo fit = {});

  // Bead width [mm] for layer height `height_mm` (> 0). Outside the fitted height range the polynomial is still
  // evaluated; callers check InRange() (a quartic extrapolates badly).
  double Width(double height_mm) const;
  bool InRange(double height_mm) const { return height_mm >= min_height_mm_ && height_mm <= max_height_mm_; }
  int degree() const { return static_cast<int>(coefficients_.size()) - 1; }
  const std::vector<double>& coefficients() const { return coefficients_; }
  double min_height_mm() const { return min_height_mm_; }
  double max_height_mm() const { return max_height_mm_; }
  const FitInfo& fit() const { return fit_; }

  nlohmann::json ToJson() const;
  static WidthHeightModel FromJson(const nlohmann::json& j, const std::string& where);
  // Loads a file written by `waam fit width-height`. Throws InputError naming the file.
  static WidthHeightModel Load(const std::filesystem::path& path);

 private:
  std::vector<double> coefficients_;
  double min_height_mm_;
  double max_height_mm_;
  FitInfo fit_;
};

// Measured beads: layer height [mm] and width [mm].
struct WidthHeightSamples {
  std::vector<double> height_mm;
  std::vector<double> width_mm;
};

struct WidthHeightFit {
  WidthHeightModel model;
  bool ok = false;
  std::string message;
};

// Least-squares polynomial of `degree` (1..8) with Ceres. Throws InputError (naming `data.file`) for a bad degree,
// fewer than degree + 2 rows, fewer than degree + 1 distinct heights, or non-positive heights.
WidthHeightFit FitWidthHeight(const WidthHeightSamples& samples, const DataSource& data, int degree = 4);

// What to command for a wanted layer height: the speed (clamped to the feasible window), the height and width the
// models then predict, and whether the height lies inside the width model's fitted range.
struct BeadSetpoint {
  SpeedChoice speed;      // speed.achieved_mm is the height obtained [mm]
  double width_mm = 0.0;  // width at the obtained height
  bool width_in_range = true;
};

// Chooses the travel speed for `height_mm` and the width that comes with it (dissertation sec. 6.3.2.1).
BeadSetpoint SetpointForHeight(const SpeedHeightModel& speed_height, const WidthHeightModel& width_height,
                               double height_mm);

}  // namespace waam::models
