// Width-height polynomial (dissertation eq. 6.2 and 6.7): evaluation, JSON, Ceres fit, and the height setpoint.
#include "models/bead/width_height_model.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "models/core/error.h"
#include "models/fit/internal/ceres_solve.h"
#include "models/fit/model_file.h"

namespace waam::models {
namespace {

constexpr char kWidthHeightModelName[] = "width_height";
constexpr int kMaxDegree = 8;

// w_i - sum_k c_k h_i^k, Horner form (eq. 6.7 with h-bar = h / 1 mm).
struct PolynomialResidual {
  double height;
  double width;
  int num_coefficients;
  template <typename T>
  bool operator()(T const* const* c, T* residual) const {
    T value = c[0][num_coefficients - 1];
    for (int k = num_coefficients - 2; k >= 0; --k) value = value * height + c[0][k];
    residual[0] = T(width) - value;
    return true;
  }
};

}  // namespace

WidthHeightModel::WidthHeightModel(std::vector<double> coefficients, double min_height_mm, double max_height_mm,
                                   FitInfo fit)
    : coefficients_(std::move(coefficients)),
      min_height_mm_(min_height_mm),
      max_height_mm_(max_height_mm),
      fit_(std::move(fit)) {}

double WidthHeightModel::Width(double height_mm) const {
  WAAM_THROW_UNLESS(height_mm > 0.0, "width-height model: layer height " << height_mm << " mm: must be > 0");
  double value = 0.0;
  for (auto it = coefficients_.rbegin(); it != coefficients_.rend(); ++it) value = value * height_mm + *it;
  return value;
}

nlohmann::json WidthHeightModel::ToJson() const {
  nlohmann::json j;
  j["model"] = kWidthHeightModelName;
  j["format_version"] = kModelFormatVersion;
  j["formula"] = "w = sum_k c[k] * h^k";
  j["source"] = "Nguyen 2022 dissertation, sec. 6.3.2.1, eq. 6.7 and Table 18";
  j["params"] = {{"degree", degree()}, {"c", coefficients_}};
  j["units"] = {{"w", "mm"}, {"h", "mm (used as h / 1 mm)"}, {"c", "mm"}};
  j["height_range_mm"] = {{"min", min_height_mm_}, {"max", max_height_mm_}};
  j["fit"] = waam::models::ToJson(fit_);
  return j;
}

WidthHeightModel WidthHeightModel::FromJson(const nlohmann::json& j, const std::string& where) {
  const nlohmann::json::json_pointer c_ptr("/params/c");
  WAAM_THROW_UNLESS(j.contains(c_ptr) && j.at(c_ptr).is_array() && !j.at(c_ptr).empty(),
                    where << ": /params/c must be a non-empty array of numbers");
  std::vector<double> c;
  for (const auto& v : j.at(c_ptr)) {
    WAAM_THROW_UNLESS(v.is_number(), where << ": /params/c must hold only numbers");
    c.push_back(v.get<double>());
  }
  return WidthHeightModel(std::move(c), JsonNumber(j, "/height_range_mm/min", where),
                          JsonNumber(j, "/height_range_mm/max", where), FitInfoFromJson(j, where));
}

WidthHeightModel WidthHeightModel::Load(const std::filesystem::path& path) {
  return FromJson(ReadModelJson(path, kWidthHeightModelName), path.string());
}

WidthHeightFit FitWidthHeight(const WidthHeightSamples& s, const DataSource& data, int degree) {
  const std::size_t n = s.height_mm.size();
  WAAM_THROW_UNLESS(degree >= 1 && degree <= kMaxDegree,
                    "width-height degree " << degree << ": must be between 1 and " << kMaxDegree);
  WAAM_THROW_UNLESS(s.width_mm.size() == n, data.file << ": height and width columns differ in length");
  const std::size_t num_params = static_cast<std::size_t>(degree) + 1;
  WAAM_THROW_UNLESS(n >= num_params + 1, data.file << ": " << n << " rows: a degree-" << degree << " polynomial has "
                                                   << num_params << " parameters and needs at least "
                                                   << num_params + 1 << " rows");
  for (std::size_t i = 0; i < n; ++i) {
    WAAM_THROW_UNLESS(s.height_mm[i] > 0.0,
                      data.file << ": row " << i + 1 << ": height " << s.height_mm[i] << " mm must be > 0");
  }
  const std::set<double> distinct(s.height_mm.begin(), s.height_mm.end());
  WAAM_THROW_UNLESS(distinct.size() >= num_params, data.file << ": only " << distinct.size()
                                                             << " distinct heights for a degree-" << degree
                                                             << " polynomial (need " << num_params << ")");

  std::vector<double> c(num_params, 0.0);
  const double mean_width = [&] {
    double sum = 0.0;
    for (double w : s.width_mm) sum += w;
    return sum / static_cast<double>(n);
  }();
  c[0] = mean_width;
  ceres::Problem problem;
  for (std::size_t i = 0; i < n; ++i) {
    auto* cost = new ceres::DynamicAutoDiffCostFunction<PolynomialResidual, 8>(
        new PolynomialResidual{s.height_mm[i], s.width_mm[i], static_cast<int>(num_params)});
    cost->AddParameterBlock(static_cast<int>(num_params));
    cost->SetNumResiduals(1);
    problem.AddResidualBlock(cost, nullptr, c.data());
  }
  FitInfo info;
  info.fitted = true;
  info.data = data;
  info.solver = internal::Solve(internal::DefaultSolverOptions(), &problem);
  const auto [lo, hi] = std::minmax_element(s.height_mm.begin(), s.height_mm.end());
  WidthHeightModel candidate(c, *lo, *hi);
  std::vector<double> predicted(n);
  for (std::size_t i = 0; i < n; ++i) predicted[i] = candidate.Width(s.height_mm[i]);
  info.stats = ComputeFitStats(s.width_mm, predicted, static_cast<int>(num_params));
  WidthHeightFit fit{WidthHeightModel(c, *lo, *hi, info), info.solver.usable, ""};
  if (!fit.ok) fit.message = "Ceres: " + std::string(NameOf(info.solver.termination)) + ": " + info.solver.message;
  return fit;
}

BeadSetpoint SetpointForHeight(const SpeedHeightModel& speed_height, const WidthHeightModel& width_height,
                               double height_mm) {
  BeadSetpoint setpoint;
  setpoint.speed = speed_height.SpeedForHeight(height_mm);
  setpoint.width_mm = width_height.Width(setpoint.speed.achieved_mm);
  setpoint.width_in_range = width_height.InRange(setpoint.speed.achieved_mm);
  return setpoint;
}

}  // namespace waam::models
