// Speed-height power law (dissertation sec. 6.3.2.1, eq. 6.1 and 6.6): forward, inverse, JSON, Ceres fit.
#include "models/bead/speed_height_model.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "models/core/error.h"
#include "models/fit/internal/ceres_solve.h"
#include "models/fit/model_file.h"

namespace waam::models {
namespace {

constexpr char kSpeedHeightModelName[] = "speed_height";

// v_i - a h_i^b (eq. 6.6 with h-bar = h / 1 mm).
struct SpeedResidual {
  double height;
  double speed;
  template <typename T>
  bool operator()(const T* ab, T* residual) const {
    residual[0] = T(speed) - ab[0] * pow(T(height), ab[1]);
    return true;
  }
};

// ln v_i - (ln a + b ln h_i), parameterised by (a, b) so both spaces share one parameter block.
struct LogSpeedResidual {
  double log_height;
  double log_speed;
  template <typename T>
  bool operator()(const T* ab, T* residual) const {
    residual[0] = T(log_speed) - (log(ab[0]) + ab[1] * T(log_height));
    return true;
  }
};

}  // namespace

SpeedHeightModel::SpeedHeightModel(SpeedHeightParams params, SpeedRange feasible, FitInfo fit, PowerLawSpace space)
    : params_(params), feasible_(feasible), fit_(std::move(fit)), space_(space) {}

double SpeedHeightModel::Speed(double height_mm) const {
  WAAM_THROW_UNLESS(height_mm > 0.0, "speed-height model: layer height " << height_mm << " mm: must be > 0");
  return params_.a * std::pow(height_mm, params_.b);
}

double SpeedHeightModel::Height(double speed_mm_per_min) const {
  WAAM_THROW_UNLESS(speed_mm_per_min > 0.0,
                    "speed-height model: travel speed " << speed_mm_per_min << " mm/min: must be > 0");
  WAAM_THROW_UNLESS(params_.b != 0.0 && params_.a > 0.0,
                    "speed-height model: a = " << params_.a << ", b = " << params_.b << ": need a > 0 and b != 0");
  return std::pow(speed_mm_per_min / params_.a, 1.0 / params_.b);
}

SpeedChoice SpeedHeightModel::SpeedForHeight(double height_mm) const {
  SpeedChoice choice = ClampSpeed(Speed(height_mm), feasible_);
  choice.achieved_mm = Height(choice.speed_mm_per_min);
  return choice;
}

nlohmann::json SpeedHeightModel::ToJson() const {
  nlohmann::json j;
  j["model"] = kSpeedHeightModelName;
  j["format_version"] = kModelFormatVersion;
  j["formula"] = "v = a * h^b";
  j["source"] = "Nguyen 2022 dissertation, sec. 6.3.2.1, eq. 6.6 and Table 18";
  j["params"] = {{"a", params_.a}, {"b", params_.b}};
  j["units"] = {{"v", "mm/min"}, {"h", "mm (used as h / 1 mm)"}, {"a", "mm/min"}, {"b", "1"}};
  j["fit_space"] = std::string(NameOf(space_));
  j["feasible_speed_mm_per_min"] = waam::models::ToJson(feasible_);
  j["fit"] = waam::models::ToJson(fit_);
  if (fit_.fitted) j["fit"]["stats_log_v"] = waam::models::ToJson(log_stats_);
  return j;
}

SpeedHeightModel SpeedHeightModel::FromJson(const nlohmann::json& j, const std::string& where) {
  SpeedHeightParams p{JsonNumber(j, "/params/a", where), JsonNumber(j, "/params/b", where)};
  WAAM_THROW_UNLESS(j.contains("feasible_speed_mm_per_min"), where << ": /feasible_speed_mm_per_min is missing");
  const std::string space_name = j.value("fit_space", std::string(NameOf(PowerLawSpace::kLinear)));
  const std::optional<PowerLawSpace> space = ParseEnum<PowerLawSpace>(space_name);
  WAAM_THROW_UNLESS(space, where << ": /fit_space = '" << space_name << "': must be "
                                 << EnumNameList<PowerLawSpace>(" or "));
  SpeedHeightModel model(p, SpeedRangeFromJson(j["feasible_speed_mm_per_min"], where), FitInfoFromJson(j, where),
                         *space);
  const nlohmann::json::json_pointer log_ptr("/fit/stats_log_v");
  if (j.contains(log_ptr)) model.set_log_stats(FitStatsFromJson(j.at(log_ptr), where));
  return model;
}

SpeedHeightModel SpeedHeightModel::Load(const std::filesystem::path& path) {
  return FromJson(ReadModelJson(path, kSpeedHeightModelName), path.string());
}

SpeedHeightFit FitSpeedHeight(const SpeedHeightSamples& s, const DataSource& data, PowerLawSpace space,
                              const SpeedRange* feasible) {
  const std::size_t n = s.height_mm.size();
  WAAM_THROW_UNLESS(s.speed_mm_per_min.size() == n, data.file << ": speed and height columns differ in length");
  WAAM_THROW_UNLESS(n >= 3, data.file << ": " << n << " rows: the power law has 2 parameters and needs at least 3 rows");
  for (std::size_t i = 0; i < n; ++i) {
    WAAM_THROW_UNLESS(s.speed_mm_per_min[i] > 0.0 && s.height_mm[i] > 0.0,
                      data.file << ": row " << i + 1 << ": speed " << s.speed_mm_per_min[i] << " mm/min and height "
                                << s.height_mm[i] << " mm must both be > 0");
  }
  const SpeedRange range = FitSpeedRange(s.speed_mm_per_min, feasible, data.file);

  // Start from the least-squares line ln v = ln a + b ln h (closed form), then refine in the chosen space.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = std::log(s.height_mm[i]), y = std::log(s.speed_mm_per_min[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double dn = static_cast<double>(n);
  const double denom = dn * sxx - sx * sx;
  WAAM_THROW_UNLESS(denom > 1e-12 * dn * sxx,
                    data.file << ": all heights are equal: a speed-height law cannot be fitted");
  const double b0 = (dn * sxy - sx * sy) / denom;
  double ab[2] = {std::exp((sy - b0 * sx) / dn), b0};

  ceres::Problem problem;
  for (std::size_t i = 0; i < n; ++i) {
    if (space == PowerLawSpace::kLog) {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<LogSpeedResidual, 1, 2>(new LogSpeedResidual{
                                   std::log(s.height_mm[i]), std::log(s.speed_mm_per_min[i])}),
                               nullptr, ab);
    } else {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SpeedResidual, 1, 2>(
                                   new SpeedResidual{s.height_mm[i], s.speed_mm_per_min[i]}),
                               nullptr, ab);
    }
  }
  problem.SetParameterLowerBound(ab, 0, 1e-12);  // a > 0 keeps ln a defined
  FitInfo info;
  info.fitted = true;
  info.data = data;
  info.solver = internal::Solve(internal::DefaultSolverOptions(), &problem);
  const SpeedHeightParams params{ab[0], ab[1]};
  SpeedHeightModel candidate(params, range);
  std::vector<double> predicted(n);
  for (std::size_t i = 0; i < n; ++i) predicted[i] = candidate.Speed(s.height_mm[i]);
  info.stats = ComputeFitStats(s.speed_mm_per_min, predicted, 2);
  std::vector<double> log_measured(n), log_predicted(n);
  for (std::size_t i = 0; i < n; ++i) {
    log_measured[i] = std::log(s.speed_mm_per_min[i]);
    log_predicted[i] = std::log(predicted[i]);
  }
  SpeedHeightFit fit{SpeedHeightModel(params, range, info, space), info.solver.usable, ""};
  fit.model.set_log_stats(ComputeFitStats(log_measured, log_predicted, 2));
  if (!fit.ok) fit.message = "Ceres: " + std::string(NameOf(info.solver.termination)) + ": " + info.solver.message;
  return fit;
}

}  // namespace waam::models
