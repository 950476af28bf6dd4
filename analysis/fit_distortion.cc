// `waam fit distortion`: the scan of a built part and its scenario -> twin build -> Ceres fit of the inherent-strain
// parameters -> the distortion model JSON with a record of the fit.
#include <chrono>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <utility>

#include "analysis/fit_internal.h"
#include "analysis/scenario.h"
#include "models/core/error.h"
#include "models/core/progress.h"
#include "models/distortion/distortion_params.h"
#include "models/fit/model_file.h"
#include "planner/plan_scenario.h"
#include "planner/scenario/scenario.h"
#include "twin/compensation/compensation.h"
#include "twin/distortion/deposit_history.h"
#include "twin/distortion/distortion_fit.h"
#include "analysis/point_cloud_file.h"
#include "twin/simulation.h"

namespace waam::analysis {
namespace {

// STL scans are sampled at this spacing (mm), as `waam compensate --scan` reads them.
constexpr double kStlSpacingMm = 0.5;
// The twin deposits the path with reference points this far apart (mm), as the compensation loop does, so that a scan
// written by `waam compensate` is of the very part this fit deposits.
constexpr double kReferenceSpacingMm = 2.0;

std::string Join(const std::vector<models::DistortionParam>& items) {
  std::string s;
  for (const models::DistortionParam item : items) {
    if (!s.empty()) s += ",";
    s += NameOf(item);
  }
  return s;
}

// The fit's start and settings from the command's options, every one checked before the expensive build.
struct DistortionFitSetup {
  std::filesystem::path start_path;
  models::DistortionParams start;
  twin::DistortionOptions distortion;
  twin::DistortionFitOptions fit;
};

DistortionFitSetup CheckedSetup(const FitOptions& options) {
  WAAM_THROW_UNLESS(!options.output.empty(), "-o/--output: the model JSON file to write is required");
  WAAM_THROW_UNLESS(!options.scenario.empty(),
                    "fit distortion: --scenario is required (the scenario YAML the scanned part was built from)");
  WAAM_THROW_UNLESS(options.columns.empty() && !options.speed_range,
                    "fit distortion: --columns and --speed-range apply to CSV models only");
  DistortionFitSetup s;
  s.start_path = options.start.empty() ? models::DefaultModelPath("distortion") : options.start;
  s.start = models::ReadDistortionParams(s.start_path);
  s.distortion.mode =
      options.mode.empty() ? s.start.mode : models::ParseDistortionMode(options.mode, "distortion.mode");
  s.distortion.element_mm = options.element_mm;
  s.distortion.groups = options.groups;
  twin::ValidateDistortionOptions(s.distortion);
  s.start.mode = s.distortion.mode;
  s.fit.free.clear();
  for (const std::string& name : options.free) {
    s.fit.free.push_back(models::ParseDistortionParam(name, "distortion fit: free parameter"));
  }
  s.fit.max_points = options.max_points;
  s.fit.max_iterations = options.max_iterations;
  twin::ValidateDistortionFitOptions(s.fit, s.distortion.mode);
  return s;
}

// Prints the free parameters' start and fitted values, the rms, the solver's summary and the wall time; returns the
// free parameters' start and fitted values by name.
std::pair<nlohmann::json, nlohmann::json> PrintFit(const DistortionFitSetup& setup,
                                                   const twin::DistortionFitResult& result, double wall_s,
                                                   std::ostream& out) {
  out << std::setprecision(6);
  nlohmann::json start_json, fitted_json;
  for (const models::DistortionParam param : setup.fit.free) {
    const std::string name(NameOf(param));
    const double a = models::ParamValue(setup.start, param), b = models::ParamValue(result.params, param);
    start_json[name] = a;
    fitted_json[name] = b;
    out << "  " << std::left << std::setw(26) << name << std::right << " = " << b << "  (start " << a << ")\n";
  }
  out << "  rms      = " << result.initial_rms_mm << " mm at the start -> " << result.rms_mm
      << " mm fitted (point-to-plane residuals, " << result.points << " scan points)\n";
  PrintSolver(out, result.solver);
  out << "  wall     = " << std::setprecision(3) << wall_s << " s (plan, deposit and fit)\n";
  return {start_json, fitted_json};
}

// The record of the fit written into the model JSON: its inputs, settings, parameters and solver summary.
nlohmann::json FitRecord(const FitOptions& options, const std::string& scenario_name, const DistortionFitSetup& setup,
                         const ScanCloud& cloud, const twin::DistortionFitResult& result,
                         const nlohmann::json& start_json, const nlohmann::json& fitted_json) {
  return {
      {"scan", options.data.string()},
      {"scan_points", cloud.points.size()},
      {"points_used", result.points},
      {"weighting", cloud.area_weighted ? "area" : "point"},
      {"scenario", scenario_name},
      {"scenario_file", options.scenario.string()},
      {"overrides", options.overrides},
      {"start_file", setup.start_path.string()},
      {"mode", setup.distortion.mode},
      {"element_mm", setup.distortion.element_mm},
      {"groups", setup.distortion.groups},
      {"free", setup.fit.free},
      {"start", start_json},
      {"fitted", fitted_json},
      {"rms_start_mm", result.initial_rms_mm},
      {"rms_mm", result.rms_mm},
      {"residual", "signed distance of each scan point to the distorted twin surface, mm (Huber loss, 1 mm)"},
      {"solver", models::ToJson(result.solver)},
  };
}

}  // namespace

FitOutcome internal::RunFitDistortion(const FitOptions& options, std::ostream& out) {
  const auto wall_start = std::chrono::steady_clock::now();
  const DistortionFitSetup setup = CheckedSetup(options);
  const models::DistortionParams& start = setup.start;
  const twin::DistortionOptions& distortion = setup.distortion;
  const twin::DistortionFitOptions& fit = setup.fit;
  // An STL's points weighted by the area each stands for, without the face the part stands on (as waam deviation).
  const ScanCloud cloud = ReadScan(options.data, kStlSpacingMm, /*skip_bottom=*/true);
  const std::vector<Eigen::Vector3d>& scan = cloud.points;
  WAAM_THROW_UNLESS(scan.size() >= 10, options.data.string() << ": the scan has " << scan.size()
                                                             << " points: the fit needs at least 10");
  const Scenario scenario = LoadScenario(options.scenario, options.overrides);

  out << "waam fit distortion: " << options.data.string() << " (" << scan.size() << " points) against scenario "
      << scenario.name << ", mode " << NameOf(distortion.mode) << ", free " << Join(fit.free) << "\n";
  planner::PlanResult planned;
  {
    Progress progress("plan", 0, "layers", options.quiet);
    planned = planner::PlanScenario(scenario, &progress);
  }
  WAAM_THROW_UNLESS(!planned.plan.layers.empty(), options.scenario.string() << ": the plan has no layers to deposit");
  const planner::Plan plan = twin::ResamplePlan(planned.plan, kReferenceSpacingMm);
  const double rapid_mm_s = scenario.process.rapid_speed_mm_min / 60.0;
  const twin::TwinResult build = [&] {
    Progress progress("deposit", 0, "passes", options.quiet);
    return twin::MeasureBuild(plan, twin::DepositPlan(plan, scenario.simulation, rapid_mm_s, &progress), nullptr,
                              scenario.path.bead_width_mm);
  }();
  const twin::DepositHistory history(plan, build.depositor, scenario.simulation, rapid_mm_s,
                                     scenario.process.wire_feed_mm_min / 60.0);
  twin::DistortionFitResult result;
  {
    Progress progress("fit", static_cast<std::size_t>(fit.max_iterations), "Ceres iterations", options.quiet);
    result = twin::FitDistortion(build.depositor.grid(), history, scan, start, distortion, fit,
                                 [&](int i) { progress.Update(static_cast<std::size_t>(i)); }, cloud.weight);
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  const auto [start_json, fitted_json] = PrintFit(setup, result, wall_s, out);
  const nlohmann::json record =
      FitRecord(options, scenario.name, setup, cloud, result, start_json, fitted_json);
  // A fit Ceres stopped short of convergence (iteration limit, failure) is not written: its parameters are not a fit.
  bool ok = result.solver.usable && result.solver.termination == models::SolverTermination::kConvergence;
  std::string message;
  if (!ok) {
    std::ostringstream why;
    why << "Ceres " << NameOf(result.solver.termination) << " after " << result.solver.iterations << " iterations ("
        << result.solver.message << "); rms " << result.rms_mm
        << " mm. Check that the scan is of this scenario's part, aligned in its part frame, or raise --max-iter";
    message = why.str();
  }
  return Finish(ok, message, models::DistortionParamsToJson(result.params, &record), options, out);
}

}  // namespace waam::analysis
