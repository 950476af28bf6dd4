// Bead-vs-interpass-temperature model: the factors, its JSON file and the Ceres fit.
#include "models/bead/bead_temperature_model.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "models/core/error.h"
#include "models/fit/internal/ceres_solve.h"
#include "models/fit/model_file.h"

namespace waam::models {
namespace {

constexpr char kBeadTemperatureModelName[] = "bead_temperature";

// Residuals of one bead at dT = T - T_ref: [h - h_ref (1 + k_h dT), w - w_ref (1 + k_w dT)]; parameters
// (h_ref, k_h, w_ref, k_w).
struct BeadLinearResidual {
  double dt, height, width;
  template <typename T>
  bool operator()(const T* p, T* r) const {
    r[0] = T(height) - p[0] * (T(1.0) + p[1] * dt);
    r[1] = T(width) - p[2] * (T(1.0) + p[3] * dt);
    return true;
  }
};

// Volume-conserving bead: [h - h_ref (1 + k_h dT), w - w_ref / (1 + k_h dT)]; parameters (h_ref, k_h, w_ref).
struct BeadVolumeResidual {
  double dt, height, width;
  template <typename T>
  bool operator()(const T* p, T* r) const {
    const T f = T(1.0) + p[1] * dt;
    r[0] = T(height) - p[0] * f;
    r[1] = T(width) - p[2] / f;
    return true;
  }
};

}  // namespace

BeadTemperatureModel::BeadTemperatureModel(BeadTemperatureParams params, double h_ref_mm, double w_ref_mm,
                                           FitInfo fit)
    : params_(params), h_ref_mm_(h_ref_mm), w_ref_mm_(w_ref_mm), fit_(std::move(fit)) {
  const BeadTemperatureParams& p = params_;
  WAAM_THROW_UNLESS(std::isfinite(p.reference_c) && std::isfinite(p.height_per_k) && std::isfinite(p.width_per_k),
                    "bead-temperature model: reference_c, height_per_k and width_per_k must be finite");
  WAAM_THROW_UNLESS(std::isfinite(p.min_c) && std::isfinite(p.max_c) && p.min_c <= p.max_c,
                    "bead-temperature model: temperature range [" << p.min_c << ", " << p.max_c
                                                                  << "] degC: must have min_c <= max_c");
  WAAM_THROW_UNLESS(p.reference_c >= p.min_c && p.reference_c <= p.max_c,
                    "bead-temperature model: reference_c = " << p.reference_c << " degC: must lie in the range ["
                                                             << p.min_c << ", " << p.max_c << "] degC");
  // The factors are linear in T: positive over the range when positive at both ends.
  for (double t : {p.min_c, p.max_c}) {
    WAAM_THROW_UNLESS(HeightFactor(t) > 0.0 && WidthFactor(t) > 0.0,
                      "bead-temperature model: at " << t << " degC the height factor " << HeightFactor(t)
                                                    << " or width factor " << WidthFactor(t) << ": must be > 0");
  }
}

double BeadTemperatureModel::Clamp(double interpass_c) const {
  // Outside the measured range the line is held at its end value (as the material tables are held beyond theirs).
  return std::clamp(interpass_c, params_.min_c, params_.max_c);
}

double BeadTemperatureModel::HeightFactor(double interpass_c) const {
  // At T_ref: 1.0 + k * 0.0 == 1.0 exactly, so h * factor == h bit for bit.
  return 1.0 + params_.height_per_k * (Clamp(interpass_c) - params_.reference_c);
}

double BeadTemperatureModel::WidthFactor(double interpass_c) const {
  if (params_.volume_conserving) return 1.0 / HeightFactor(interpass_c);
  return 1.0 + params_.width_per_k * (Clamp(interpass_c) - params_.reference_c);
}

nlohmann::json BeadTemperatureModel::ToJson() const {
  nlohmann::json j;
  j["model"] = kBeadTemperatureModelName;
  j["format_version"] = kModelFormatVersion;
  j["formula"] = params_.volume_conserving
                     ? "h = h_ref * (1 + k_h * (T - T_ref)), w = w_ref / (1 + k_h * (T - T_ref)), T clamped to range"
                     : "h = h_ref * (1 + k_h * (T - T_ref)), w = w_ref * (1 + k_w * (T - T_ref)), T clamped to range";
  j["source"] = "bead height and width against the local interpass temperature (waam-twin, docs/compensation.md)";
  j["params"] = {{"reference_c", params_.reference_c},      {"height_per_k", params_.height_per_k},
                 {"width_per_k", params_.width_per_k},      {"volume_conserving", params_.volume_conserving},
                 {"h_ref_mm", h_ref_mm_},                   {"w_ref_mm", w_ref_mm_}};
  j["temperature_range_c"] = {{"min", params_.min_c}, {"max", params_.max_c}};
  j["units"] = {{"T", "degC"}, {"reference_c", "degC"}, {"height_per_k", "1/K"}, {"width_per_k", "1/K"},
                {"h_ref_mm", "mm"}, {"w_ref_mm", "mm"}};
  j["fit"] = waam::models::ToJson(fit_);
  if (width_stats_.n > 0) j["fit"]["width_stats"] = waam::models::ToJson(width_stats_);
  return j;
}

BeadTemperatureModel BeadTemperatureModel::FromJson(const nlohmann::json& j, const std::string& where) {
  BeadTemperatureParams p;
  p.reference_c = JsonNumber(j, "/params/reference_c", where);
  p.height_per_k = JsonNumber(j, "/params/height_per_k", where);
  p.width_per_k = JsonNumber(j, "/params/width_per_k", where);
  const nlohmann::json::json_pointer volume("/params/volume_conserving");
  WAAM_THROW_UNLESS(j.contains(volume) && j.at(volume).is_boolean(),
                    where << ": /params/volume_conserving is missing or not true/false");
  p.volume_conserving = j.at(volume).get<bool>();
  p.min_c = JsonNumber(j, "/temperature_range_c/min", where);
  p.max_c = JsonNumber(j, "/temperature_range_c/max", where);
  try {
    BeadTemperatureModel model(p, JsonNumber(j, "/params/h_ref_mm", where), JsonNumber(j, "/params/w_ref_mm", where),
                               FitInfoFromJson(j, where));
    const nlohmann::json::json_pointer width("/fit/width_stats");
    if (j.contains(width)) model.set_width_stats(FitStatsFromJson(j.at(width), where));
    return model;
  } catch (const InputError& e) {
    WAAM_THROW(where << ": " << e.what());
  }
}

BeadTemperatureModel BeadTemperatureModel::Load(const std::filesystem::path& path) {
  return FromJson(ReadModelJson(path, kBeadTemperatureModelName), path.string());
}

BeadTemperatureFit FitBeadTemperature(const BeadTemperatureSamples& s, const DataSource& data, double reference_c,
                                      bool volume_conserving) {
  const std::size_t n = s.interpass_c.size();
  WAAM_THROW_UNLESS(s.height_mm.size() == n && s.width_mm.size() == n,
                    data.file << ": interpass, height and width columns differ in length");
  WAAM_THROW_UNLESS(n >= 4, data.file << ": " << n << " rows: the bead-temperature model needs at least 4 rows");
  WAAM_THROW_UNLESS(std::isfinite(reference_c), data.file << ": reference temperature must be finite");
  std::set<double> distinct;
  double h_mean = 0.0, w_mean = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    WAAM_THROW_UNLESS(s.height_mm[i] > 0.0 && s.width_mm[i] > 0.0,
                      data.file << ": row " << i + 1 << ": height " << s.height_mm[i] << " mm and width "
                                << s.width_mm[i] << " mm must both be > 0");
    distinct.insert(s.interpass_c[i]);
    h_mean += s.height_mm[i] / n;
    w_mean += s.width_mm[i] / n;
  }
  WAAM_THROW_UNLESS(distinct.size() >= 2,
                    data.file << ": every row has interpass temperature " << *distinct.begin()
                              << " degC: the slope needs at least 2 distinct temperatures");
  // Start at the means with no slope: the problem is almost linear and LM converges in a few steps.
  double p[4] = {h_mean, 0.0, w_mean, 0.0};
  ceres::Problem problem;
  for (std::size_t i = 0; i < n; ++i) {
    const double dt = s.interpass_c[i] - reference_c;
    if (volume_conserving) {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<BeadVolumeResidual, 2, 3>(
                                   new BeadVolumeResidual{dt, s.height_mm[i], s.width_mm[i]}),
                               nullptr, p);
    } else {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<BeadLinearResidual, 2, 4>(
                                   new BeadLinearResidual{dt, s.height_mm[i], s.width_mm[i]}),
                               nullptr, p);
    }
  }
  FitInfo info;
  info.fitted = true;
  info.data = data;
  info.solver = internal::Solve(internal::DefaultSolverOptions(), &problem);
  BeadTemperatureParams params;
  params.reference_c = reference_c;
  params.height_per_k = p[1];
  params.width_per_k = volume_conserving ? 0.0 : p[3];
  params.volume_conserving = volume_conserving;
  params.min_c = std::min(*distinct.begin(), reference_c);
  params.max_c = std::max(*distinct.rbegin(), reference_c);
  std::vector<double> h_pred(n), w_pred(n);
  auto factor_ok = [&](double t) { return 1.0 + params.height_per_k * (t - reference_c) > 0.0; };
  const bool usable = info.solver.usable && p[0] > 0.0 && p[2] > 0.0 && factor_ok(params.min_c) &&
                      factor_ok(params.max_c) &&
                      (volume_conserving || (1.0 + params.width_per_k * (params.min_c - reference_c) > 0.0 &&
                                             1.0 + params.width_per_k * (params.max_c - reference_c) > 0.0));
  if (!usable) {
    BeadTemperatureParams neutral;
    neutral.reference_c = reference_c;
    neutral.min_c = params.min_c;
    neutral.max_c = params.max_c;
    const std::string why = info.solver.usable ? "the fitted line is not positive over the data's temperatures"
                                               : "Ceres: " + std::string(NameOf(info.solver.termination)) + ": " + info.solver.message;
    return {BeadTemperatureModel(neutral, 0.0, 0.0, info), false, why};
  }
  BeadTemperatureModel model(params, p[0], p[2], info);
  for (std::size_t i = 0; i < n; ++i) {
    h_pred[i] = p[0] * model.HeightFactor(s.interpass_c[i]);
    w_pred[i] = p[2] * model.WidthFactor(s.interpass_c[i]);
  }
  info.stats = ComputeFitStats(s.height_mm, h_pred, 2);
  BeadTemperatureModel fitted(params, p[0], p[2], info);
  fitted.set_width_stats(ComputeFitStats(s.width_mm, w_pred, volume_conserving ? 1 : 2));
  return {fitted, true, ""};
}

}  // namespace waam::models
