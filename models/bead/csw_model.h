// Curvature-speed-width (CSW) bead model of Dai et al. 2020: width from travel speed and path curvature radius.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/bead/speed_range.h"
#include "models/fit/fit_stats.h"

namespace waam::models {

// Coefficients of w = m v^(-1/3) + p / r + t (w, r, t in mm; v in mm/min; p in mm^2; m in mm (mm/min)^(1/3)).
struct CswParams {
  double m = 0.0;
  double p = 0.0;
  double t = 0.0;
};

// The CSW model with the feasible speed window it may be inverted in and the record of its fit.
class CswModel {
 public:
  CswModel(CswParams params, SpeedRange feasible, FitInfo fit = {});

  // Bead width [mm] at travel speed `speed_mm_per_min` (> 0) on a path of curvature radius `radius_mm`
  // (> 0; +inf for a straight line).
  double Width(double speed_mm_per_min, double radius_mm) const;
  // The travel speed that gives `width_mm` on radius `radius_mm`, clamped to the feasible window; the clamp and
  // the width actually obtained are reported. Throws InputError if m <= 0 (width would not fall with speed).
  SpeedChoice SpeedForWidth(double width_mm, double radius_mm) const;
  // The radius (mm) to evaluate the model at for a bead `bead_width_mm` wide on a path of local curvature radius
  // `radius_mm`; the planner's speed choice and the twin's widening use the same rule. +inf (straight) below one
  // bead width: that is a corner, for which the model has no term (the swept bead shapes it). Otherwise at least
  // `min_radius_mm` (> 0), the smallest radius of the data the model was fitted to (30 mm in Dai's Table 1): p/r
  // grows without bound below it (p = 52.7 mm^2 gives 53 mm of extra width at r = 1 mm).
  static double ApplicableRadius(double radius_mm, double bead_width_mm, double min_radius_mm);

  const CswParams& params() const { return params_; }
  const SpeedRange& feasible() const { return feasible_; }
  const FitInfo& fit() const { return fit_; }

  nlohmann::json ToJson() const;
  // Builds the model from ToJson() output; `where` names the file in errors. Throws InputError.
  static CswModel FromJson(const nlohmann::json& j, const std::string& where);
  // Loads a model file written by `waam fit csw`. Throws InputError naming the file.
  static CswModel Load(const std::filesystem::path& path);

 private:
  CswParams params_;
  SpeedRange feasible_;
  FitInfo fit_;
};

// Measured single beads: speed [mm/min], curvature radius [mm] (+inf = straight), width [mm], one entry each.
struct CswSamples {
  std::vector<double> speed_mm_per_min;
  std::vector<double> radius_mm;
  std::vector<double> width_mm;
};

// Result of a fit: the model (with its FitInfo) and whether the solver's answer is usable.
struct CswFit {
  CswModel model;
  bool ok = false;
  std::string message;  // why the fit failed, when !ok
};

// Least-squares fit of (m, p, t) to `samples` with Ceres; the feasible window defaults to the data's speed range.
// Throws InputError (naming `data.file`) for fewer than 4 samples or non-positive speeds or radii.
CswFit FitCsw(const CswSamples& samples, const DataSource& data, const SpeedRange* feasible = nullptr);

}  // namespace waam::models
