// Junction geometry and the common interface of junction void-length models (dissertation sec. 4.4.2, eq. 4.7).
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/fit/fit_stats.h"

namespace waam::models {

// A rib junction as the dissertation parameterises it (Appendix A1): eta = number of turning points and the four
// angles between neighbouring ribs [deg], theta1 the largest, the rest in the order printed (going round the
// junction), theta4 = 0 for a three-rib junction.
struct Junction {
  int turning_points = 0;
  std::array<double, 4> angles_deg{};

  // Smallest non-zero angle [deg] (theta_min of eq. 4.6).
  double SmallestAngleDeg() const;
  // Throws InputError ("<where>: ...") unless eta >= 1 and the angles are in [0, 360] with at least three > 0.
  void Validate(const std::string& where) const;
};

// One measured junction: its geometry, the measured void length [mm], and its label (e.g. "F7").
struct JunctionSample {
  Junction junction;
  double void_length_mm = 0.0;
  std::string label;
};

// A model that predicts the void length at a junction welded with the standard contour path.
class VoidLengthModel {
 public:
  virtual ~VoidLengthModel() = default;
  // Predicted void length [mm].
  virtual double PredictMm(const Junction& junction) const = 0;
  // "network" or "baseline".
  virtual std::string kind() const = 0;
  // The model file (with "model": "void_length" and "kind").
  virtual nlohmann::json ToJson() const = 0;
  virtual const FitInfo& fit() const = 0;
};

// Loads a file written by `waam fit void-length` (either kind). Throws InputError naming the file.
std::unique_ptr<VoidLengthModel> LoadVoidLengthModel(const std::filesystem::path& path);

// Trains a model of one kind on samples (used by cross-validation); returns nullptr if training failed.
using VoidLengthTrainer =
    std::function<std::unique_ptr<VoidLengthModel>(const std::vector<JunctionSample>& training)>;

// Held-out prediction quality of a trainer (dissertation sec. 4.6.3: lower tolerance -1.3 mm).
struct CrossValidationOptions {
  int folds = 5;                 // k of k-fold; ignored with leave_one_out
  bool leave_one_out = false;
  unsigned long long seed = 1;   // shuffles rows into folds
  double under_tolerance_mm = 1.3;  // a prediction below measured by more than this leaves a void unfilled
};

struct CrossValidationResult {
  std::vector<double> predicted_mm;  // held-out prediction for each sample, in sample order
  int folds = 0;
  double mae_mm = 0.0;
  double rmse_mm = 0.0;
  double max_abs_mm = 0.0;
  double share_under = 0.0;  // fraction of samples with predicted < measured - under_tolerance
  int failed_folds = 0;      // folds whose training failed (their samples are excluded from the metrics)
};

// k-fold (or leave-one-out) cross-validation of `trainer` on `samples`. Throws InputError if folds < 2 or
// folds > samples. `on_fold` (optional) is called after each fold with (done, total).
CrossValidationResult CrossValidate(const std::vector<JunctionSample>& samples, const VoidLengthTrainer& trainer,
                                    const CrossValidationOptions& options,
                                    const std::function<void(int, int)>& on_fold = nullptr);

nlohmann::json ToJson(const CrossValidationResult& cv, const CrossValidationOptions& options);

}  // namespace waam::models
