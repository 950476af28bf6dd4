// CSW model (Dai, Zhang, Li 2020, section 4): forward, inverse, JSON and the Ceres fit.
#include "models/bead/csw_model.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"
#include "models/fit/internal/ceres_solve.h"
#include "models/fit/model_file.h"

namespace waam::models {
namespace {

constexpr char kModelName[] = "csw";

// Residual of one bead: measured width minus w = m v^(-1/3) + p / r + t (Dai eq. 6 and 10 combined).
struct CswResidual {
  double inv_cbrt_speed;  // v^(-1/3)
  double curvature;       // 1 / r [1/mm], 0 for a straight line
  double width;
  template <typename T>
  bool operator()(const T* mpt, T* residual) const {
    residual[0] = T(width) - (mpt[0] * inv_cbrt_speed + mpt[1] * curvature + mpt[2]);
    return true;
  }
};

}  // namespace

CswModel::CswModel(CswParams params, SpeedRange feasible, FitInfo fit)
    : params_(params), feasible_(feasible), fit_(std::move(fit)) {}

double CswModel::Width(double speed_mm_per_min, double radius_mm) const {
  WAAM_THROW_UNLESS(speed_mm_per_min > 0.0, "CSW model: travel speed " << speed_mm_per_min << " mm/min: must be > 0");
  WAAM_THROW_UNLESS(radius_mm > 0.0, "CSW model: curvature radius " << radius_mm << " mm: must be > 0 (inf = straight)");
  return params_.m / std::cbrt(speed_mm_per_min) + params_.p / radius_mm + params_.t;
}

double CswModel::ApplicableRadius(double radius_mm, double bead_width_mm, double min_radius_mm) {
  WAAM_THROW_UNLESS(min_radius_mm > 0.0, "CSW model: minimum radius " << min_radius_mm << " mm: must be > 0");
  if (!(radius_mm >= bead_width_mm) || std::isinf(radius_mm)) return INFINITY;
  return std::max(radius_mm, min_radius_mm);
}

SpeedChoice CswModel::SpeedForWidth(double width_mm, double radius_mm) const {
  WAAM_THROW_UNLESS(params_.m > 0.0, "CSW model: m = " << params_.m << ": must be > 0 to choose a speed for a width");
  WAAM_THROW_UNLESS(width_mm > 0.0, "CSW model: wanted width " << width_mm << " mm: must be > 0");
  WAAM_THROW_UNLESS(radius_mm > 0.0, "CSW model: curvature radius " << radius_mm << " mm: must be > 0 (inf = straight)");
  // Inverse of the CSW model: v = (m / (w - p/r - t))^3. A width at or below the speed-independent part cannot be
  // reached at any speed; the fastest feasible speed comes closest.
  const double speed_part = width_mm - params_.p / radius_mm - params_.t;
  const double exact = speed_part > 0.0 ? std::pow(params_.m / speed_part, 3.0) : INFINITY;
  SpeedChoice choice = ClampSpeed(exact, feasible_);
  choice.achieved_mm = Width(choice.speed_mm_per_min, radius_mm);
  return choice;
}

nlohmann::json CswModel::ToJson() const {
  nlohmann::json j;
  j["model"] = kModelName;
  j["format_version"] = kModelFormatVersion;
  j["formula"] = "w = m * v^(-1/3) + p / r + t";
  j["source"] = "Dai, Zhang, Li 2020, Rapid Prototyping Journal 26(8), section 4 (CSW model)";
  j["params"] = {{"m", params_.m}, {"p", params_.p}, {"t", params_.t}};
  j["units"] = {{"w", "mm"}, {"v", "mm/min"}, {"r", "mm (inf = straight line)"}, {"m", "mm*(mm/min)^(1/3)"},
                {"p", "mm^2"}, {"t", "mm"}};
  j["feasible_speed_mm_per_min"] = waam::models::ToJson(feasible_);
  j["fit"] = waam::models::ToJson(fit_);
  return j;
}

CswModel CswModel::FromJson(const nlohmann::json& j, const std::string& where) {
  CswParams p{JsonNumber(j, "/params/m", where), JsonNumber(j, "/params/p", where), JsonNumber(j, "/params/t", where)};
  WAAM_THROW_UNLESS(j.contains("feasible_speed_mm_per_min"), where << ": /feasible_speed_mm_per_min is missing");
  return CswModel(p, SpeedRangeFromJson(j["feasible_speed_mm_per_min"], where), FitInfoFromJson(j, where));
}

CswModel CswModel::Load(const std::filesystem::path& path) {
  return FromJson(ReadModelJson(path, kModelName), path.string());
}

CswFit FitCsw(const CswSamples& s, const DataSource& data, const SpeedRange* feasible) {
  const std::size_t n = s.width_mm.size();
  WAAM_THROW_UNLESS(s.speed_mm_per_min.size() == n && s.radius_mm.size() == n,
                    data.file << ": speed, radius and width columns differ in length");
  WAAM_THROW_UNLESS(n >= 4, data.file << ": " << n << " rows: the CSW model has 3 parameters and needs at least 4 rows");
  for (std::size_t i = 0; i < n; ++i) {
    WAAM_THROW_UNLESS(s.speed_mm_per_min[i] > 0.0 && s.radius_mm[i] > 0.0,
                      data.file << ": row " << i + 1 << ": speed " << s.speed_mm_per_min[i] << " mm/min and radius "
                                << s.radius_mm[i] << " mm must both be > 0");
  }
  const SpeedRange range = FitSpeedRange(s.speed_mm_per_min, feasible, data.file);

  // The model is linear in (m, p, t); start from a plausible point and let LM converge in a few steps.
  double mpt[3] = {50.0, 0.0, 0.0};
  ceres::Problem problem;
  for (std::size_t i = 0; i < n; ++i) {
    auto* cost = new ceres::AutoDiffCostFunction<CswResidual, 1, 3>(
        new CswResidual{1.0 / std::cbrt(s.speed_mm_per_min[i]), 1.0 / s.radius_mm[i], s.width_mm[i]});
    problem.AddResidualBlock(cost, nullptr, mpt);
  }
  FitInfo info;
  info.fitted = true;
  info.data = data;
  info.solver = internal::Solve(internal::DefaultSolverOptions(), &problem);
  CswModel candidate(CswParams{mpt[0], mpt[1], mpt[2]}, range);
  std::vector<double> predicted(n);
  for (std::size_t i = 0; i < n; ++i) predicted[i] = candidate.Width(s.speed_mm_per_min[i], s.radius_mm[i]);
  info.stats = ComputeFitStats(s.width_mm, predicted, 3);
  CswFit fit{CswModel(candidate.params(), range, info), info.solver.usable, ""};
  if (!fit.ok) fit.message = "Ceres: " + std::string(NameOf(info.solver.termination)) + ": " + info.solver.message;
  return fit;
}

}  // namespace waam::models
