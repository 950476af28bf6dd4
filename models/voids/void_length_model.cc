// Junction checks, loading either kind of void-length model, and cross-validation.
#include "models/voids/void_length_model.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "models/core/error.h"
#include "models/core/progress.h"
#include "models/fit/model_file.h"
#include "models/voids/void_length_baseline.h"
#include "models/voids/void_length_network.h"

namespace waam::models {

double Junction::SmallestAngleDeg() const {
  double smallest = INFINITY;
  for (double a : angles_deg) {
    if (a > 0.0) smallest = std::min(smallest, a);
  }
  return smallest;
}

void Junction::Validate(const std::string& where) const {
  WAAM_THROW_UNLESS(turning_points >= 1, where << ": eta = " << turning_points << ": must be >= 1");
  int positive = 0;
  for (int k = 0; k < 4; ++k) {
    WAAM_THROW_UNLESS(std::isfinite(angles_deg[k]) && angles_deg[k] >= 0.0 && angles_deg[k] <= 360.0,
                      where << ": theta" << k + 1 << " = " << angles_deg[k] << " deg: must be in [0, 360]");
    if (angles_deg[k] > 0.0) ++positive;
  }
  WAAM_THROW_UNLESS(positive >= 3, where << ": only " << positive << " angles > 0: a junction has 3 or 4 ribs");
}

std::unique_ptr<VoidLengthModel> LoadVoidLengthModel(const std::filesystem::path& path) {
  const nlohmann::json j = ReadModelJson(path, "void_length");
  const std::string kind = j.value("kind", "");
  if (kind == "network") return std::make_unique<VoidLengthNetwork>(VoidLengthNetwork::FromJson(j, path.string()));
  if (kind == "baseline") return std::make_unique<VoidLengthBaseline>(VoidLengthBaseline::FromJson(j, path.string()));
  WAAM_THROW(path.string() << ": /kind '" << kind << "': must be network or baseline");
}

CrossValidationResult CrossValidate(const std::vector<JunctionSample>& samples, const VoidLengthTrainer& trainer,
                                    const CrossValidationOptions& options,
                                    const std::function<void(int, int)>& on_fold) {
  const int n = static_cast<int>(samples.size());
  const int folds = options.leave_one_out ? n : options.folds;
  WAAM_THROW_UNLESS(folds >= 2, "cross-validation: " << folds << " folds: must be >= 2");
  WAAM_THROW_UNLESS(folds <= n, "cross-validation: " << folds << " folds for " << n << " junctions: at most one fold "
                                                     << "per junction");
  // Seeded shuffle, then row i goes to fold (position of i) mod k.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  if (!options.leave_one_out) {
    std::mt19937_64 rng(options.seed);
    std::shuffle(order.begin(), order.end(), rng);
  }
  std::vector<int> fold_of(n);
  for (int pos = 0; pos < n; ++pos) fold_of[order[pos]] = pos % folds;

  CrossValidationResult cv;
  cv.folds = folds;
  cv.predicted_mm.assign(n, std::numeric_limits<double>::quiet_NaN());
  for (int f = 0; f < folds; ++f) {
    CheckInterrupt();
    std::vector<JunctionSample> training;
    for (int i = 0; i < n; ++i) {
      if (fold_of[i] != f) training.push_back(samples[i]);
    }
    const std::unique_ptr<VoidLengthModel> model = trainer(training);
    if (!model) {
      ++cv.failed_folds;
    } else {
      for (int i = 0; i < n; ++i) {
        if (fold_of[i] == f) cv.predicted_mm[i] = model->PredictMm(samples[i].junction);
      }
    }
    if (on_fold) on_fold(f + 1, folds);
  }
  int counted = 0, under = 0;
  double sum_abs = 0.0, sum_sq = 0.0;
  for (int i = 0; i < n; ++i) {
    if (std::isnan(cv.predicted_mm[i])) continue;
    const double error = cv.predicted_mm[i] - samples[i].void_length_mm;  // Delta L = output - target (Table 11)
    ++counted;
    sum_abs += std::abs(error);
    sum_sq += error * error;
    cv.max_abs_mm = std::max(cv.max_abs_mm, std::abs(error));
    if (error < -options.under_tolerance_mm) ++under;
  }
  if (counted > 0) {
    cv.mae_mm = sum_abs / counted;
    cv.rmse_mm = std::sqrt(sum_sq / counted);
    cv.share_under = static_cast<double>(under) / counted;
  }
  return cv;
}

nlohmann::json ToJson(const CrossValidationResult& cv, const CrossValidationOptions& options) {
  return {{"folds", cv.folds},
          {"leave_one_out", options.leave_one_out},
          {"seed", options.seed},
          {"cv_mae_mm", cv.mae_mm},
          {"cv_rmse_mm", cv.rmse_mm},
          {"cv_max_abs_mm", cv.max_abs_mm},
          {"under_tolerance_mm", options.under_tolerance_mm},
          {"cv_share_under_tolerance", cv.share_under},
          {"failed_folds", cv.failed_folds}};
}

}  // namespace waam::models
