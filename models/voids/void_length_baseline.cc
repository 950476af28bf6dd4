// Void-length baseline L = a + b (1/sin(theta_min/2) - 1): the geometric shift of eq. 4.3 as a regressor.
#include "models/voids/void_length_baseline.h"

#include <cmath>
#include <numbers>

#include "models/core/error.h"
#include "models/fit/internal/ceres_solve.h"
#include "models/fit/model_file.h"

namespace waam::models {
namespace {

struct LineResidual {
  double x;
  double y;
  template <typename T>
  bool operator()(const T* ab, T* residual) const {
    residual[0] = T(y) - (ab[0] + ab[1] * x);
    return true;
  }
};

}  // namespace

// Eq. 4.3: PP_N = l (1/sin(theta/2) - 1), the shift needed at a turning point of angle theta; eq. 4.6 relates it
// to the measured void length through theta_min.
double SharpnessTerm(const Junction& junction) {
  const double theta = junction.SmallestAngleDeg() * std::numbers::pi / 180.0;
  return 1.0 / std::sin(0.5 * theta) - 1.0;
}

VoidLengthBaseline::VoidLengthBaseline(double a_mm, double b_mm, FitInfo fit)
    : a_mm_(a_mm), b_mm_(b_mm), fit_(std::move(fit)) {}

double VoidLengthBaseline::PredictMm(const Junction& junction) const {
  return a_mm_ + b_mm_ * SharpnessTerm(junction);
}

nlohmann::json VoidLengthBaseline::ToJson() const {
  nlohmann::json j;
  j["model"] = "void_length";
  j["format_version"] = kModelFormatVersion;
  j["kind"] = "baseline";
  j["formula"] = "L = a + b * (1 / sin(theta_min / 2) - 1)";
  j["source"] = "regressor from Nguyen 2022 dissertation eq. 4.3 and 4.6";
  j["params"] = {{"a", a_mm_}, {"b", b_mm_}};
  j["units"] = {{"L", "mm"}, {"a", "mm"}, {"b", "mm"}, {"theta_min", "deg"}};
  j["fit"] = waam::models::ToJson(fit_);
  return j;
}

VoidLengthBaseline VoidLengthBaseline::FromJson(const nlohmann::json& j, const std::string& where) {
  return VoidLengthBaseline(JsonNumber(j, "/params/a", where), JsonNumber(j, "/params/b", where),
                            FitInfoFromJson(j, where));
}

VoidBaselineFit FitVoidLengthBaseline(const std::vector<JunctionSample>& samples, const DataSource& data) {
  const std::size_t n = samples.size();
  WAAM_THROW_UNLESS(n >= 3, data.file << ": " << n << " junctions: the baseline has 2 parameters and needs at least 3");
  double ab[2] = {0.0, 1.0};
  ceres::Problem problem;
  for (const JunctionSample& s : samples) {
    s.junction.Validate(data.file + ": junction " + s.label);
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<LineResidual, 1, 2>(
                                 new LineResidual{SharpnessTerm(s.junction), s.void_length_mm}),
                             nullptr, ab);
  }
  FitInfo info;
  info.fitted = true;
  info.data = data;
  info.solver = internal::Solve(internal::DefaultSolverOptions(), &problem);
  VoidBaselineFit fit;
  fit.ok = info.solver.usable;
  if (!fit.ok) fit.message = "Ceres: " + std::string(NameOf(info.solver.termination)) + ": " + info.solver.message;
  std::vector<double> measured, predicted;
  const VoidLengthBaseline candidate(ab[0], ab[1]);
  for (const JunctionSample& s : samples) {
    measured.push_back(s.void_length_mm);
    predicted.push_back(candidate.PredictMm(s.junction));
  }
  info.stats = ComputeFitStats(measured, predicted, 2);
  fit.model = std::make_unique<VoidLengthBaseline>(ab[0], ab[1], info);
  return fit;
}

}  // namespace waam::models
