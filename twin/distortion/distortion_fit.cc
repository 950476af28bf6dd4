// Ceres fit of the inherent-strain parameters to a scan of the distorted part. Derivatives by central differences:
// one distortion solve per parameter and side.
//
// The residual of a scan point s is the signed distance of its pre-image x = s - u(x) (the point the displacement
// field u carried onto s, found by fixed-point iteration from the point of the undistorted surface nearest to s, so
// that the iterates stay where u is defined even when the part moved by more than its wall thickness; |grad u| << 1
// makes it a contraction) to the undistorted deposit surface. It is zero exactly where the distorted surface x + u(x) passes through s and equals the distance of
// s to that surface to first order in grad u, yet needs the distance structure of the undistorted surface only, built
// once instead of once per evaluation. The rms reported before and after the fit is the true point-to-surface
// distance to the moved surface mesh.
#include "twin/distortion/distortion_fit.h"

#include <algorithm>
#include <cmath>

#include <ceres/ceres.h>

#include "models/core/error.h"
#include "models/core/progress.h"
#include "twin/scanner/mesh_distance.h"
#include "twin/scanner/surface_mesh.h"

namespace waam::twin {
namespace {

double* Field(models::DistortionParams* p, const std::string& name) {
  if (name == "strain") return &p->strain;
  if (name == "heat_exponent") return &p->heat_exponent;
  if (name == "vertical_ratio") return &p->vertical_ratio;
  if (name == "substrate_stiffness_n_mm3") return &p->substrate_stiffness_n_mm3;
  return nullptr;
}

// Strains and stiffnesses are fitted as logarithms (positive, and of very different sizes); the exponent as is.
bool LogScale(const std::string& name) { return name != "heat_exponent"; }

// Fixed-point iterations of the pre-image x = s - u(x): a fixed count keeps the residual a smooth function of the
// parameters for the numeric derivatives (the error shrinks as |grad u|^k, below 1e-9 of u for any real distortion).
constexpr int kPullBackIterations = 8;

struct ScanResidual {
  const VoxelGrid* grid;
  const DepositHistory* history;
  const std::vector<Eigen::Vector3d>* points;
  const std::vector<Eigen::Vector3d>* seeds;  // per point: nearest point of the undistorted surface
  const MeshDistance* undistorted;
  models::DistortionParams start;
  DistortionOptions options;
  std::vector<std::string> free;

  models::DistortionParams Params(const double* x) const {
    models::DistortionParams p = start;
    for (std::size_t k = 0; k < free.size(); ++k) *Field(&p, free[k]) = LogScale(free[k]) ? std::exp(x[k]) : x[k];
    return p;
  }
  bool operator()(double const* const* x, double* residual) const {
    const models::DistortionParams p = Params(x[0]);
    try {
      models::ValidateDistortionParams(p, "fit");
    } catch (const InputError&) {
      return false;  // outside the valid range: Ceres shortens the step
    }
    const DistortionField field = ComputeDistortion(*grid, *history, p, options);
    for (std::size_t i = 0; i < points->size(); ++i) {
      const Eigen::Vector3d& s = (*points)[i];
      Eigen::Vector3d x = (*seeds)[i];
      for (int k = 0; k < kPullBackIterations; ++k) x = s - field.Displacement(x);
      residual[i] = undistorted->SignedDistance(x);
    }
    return true;
  }
};

// Rms distance (mm) of `points` to `surface` with every vertex moved by the distortion at `params`.
double ForwardRms(const VoxelGrid& grid, const DepositHistory& history, const planner::TriangleMesh& surface,
                  const std::vector<Eigen::Vector3d>& points, const models::DistortionParams& params,
                  const DistortionOptions& options) {
  const DistortionField field = ComputeDistortion(grid, history, params, options);
  planner::TriangleMesh moved = surface;
  for (Eigen::Vector3d& v : moved.vertices) v += field.Displacement(v);
  const MeshDistance distance(moved);
  double sum = 0.0;
  for (const Eigen::Vector3d& p : points) sum += std::pow(distance.SignedDistance(p), 2);
  return std::sqrt(sum / std::max<std::size_t>(1, points.size()));
}

// Reports each iteration; stops the solve on Ctrl-C (an exception must not cross Ceres).
class IterationReporter : public ceres::IterationCallback {
 public:
  explicit IterationReporter(const std::function<void(int)>& f) : f_(f) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    try {
      if (f_) f_(summary.iteration);
    } catch (const Interrupted&) {
      return ceres::SOLVER_ABORT;
    }
    return InterruptRequested() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const std::function<void(int)>& f_;
};

}  // namespace

void ValidateDistortionFitOptions(const DistortionFitOptions& fit, const std::string& mode) {
  WAAM_THROW_UNLESS(!fit.free.empty(), "distortion fit: no free parameter");
  for (std::size_t k = 0; k < fit.free.size(); ++k) {
    const std::string& name = fit.free[k];
    models::DistortionParams probe;
    WAAM_THROW_UNLESS(Field(&probe, name) != nullptr,
                      "distortion fit: free parameter '" << name << "': must be one of strain, heat_exponent, "
                      "vertical_ratio, substrate_stiffness_n_mm3");
    for (std::size_t j = 0; j < k; ++j) {
      WAAM_THROW_UNLESS(fit.free[j] != name, "distortion fit: free parameter '" << name << "' is given twice");
    }
    // The reduced model has no substrate: its stiffness would be a free parameter with a zero Jacobian column.
    WAAM_THROW_UNLESS(!(mode == "reduced" && name == "substrate_stiffness_n_mm3"),
                      "distortion fit: free parameter 'substrate_stiffness_n_mm3' has no effect in mode reduced "
                      "(no substrate compliance): fit it in mode fe");
  }
  WAAM_THROW_UNLESS(fit.max_points >= 10, "distortion fit: max_points = " << fit.max_points << ": must be >= 10");
  WAAM_THROW_UNLESS(fit.max_iterations >= 1 && fit.max_iterations <= 1000,
                    "distortion fit: max_iterations = " << fit.max_iterations << ": must be in [1, 1000]");
}

DistortionFitResult FitDistortion(const VoxelGrid& grid, const DepositHistory& history,
                                  const std::vector<Eigen::Vector3d>& scan, const models::DistortionParams& start,
                                  const DistortionOptions& options, const DistortionFitOptions& fit,
                                  const std::function<void(int)>& on_iteration) {
  models::ValidateDistortionParams(start, "distortion fit start");
  ValidateDistortionOptions(options);
  ValidateDistortionFitOptions(fit, options.mode);
  WAAM_THROW_UNLESS(scan.size() >= 10, "distortion fit: the scan has " << scan.size() << " points: need >= 10");
  std::vector<Eigen::Vector3d> used;
  const std::size_t step = std::max<std::size_t>(1, scan.size() / fit.max_points);
  for (std::size_t i = 0; i < scan.size(); i += step) used.push_back(scan[i]);
  const planner::TriangleMesh surface = ExtractSurface(grid);
  const MeshDistance undistorted(surface);
  std::vector<Eigen::Vector3d> seeds(used.size());
  for (std::size_t i = 0; i < used.size(); ++i) undistorted.SignedDistance(used[i], &seeds[i]);

  auto* functor = new ScanResidual{&grid, &history, &used, &seeds, &undistorted, start, options, fit.free};
  std::vector<double> x(fit.free.size());
  for (std::size_t k = 0; k < fit.free.size(); ++k) {
    models::DistortionParams p = start;
    const double v = *Field(&p, fit.free[k]);
    x[k] = LogScale(fit.free[k]) ? std::log(std::max(v, 1e-12)) : v;
  }
  auto* cost = new ceres::DynamicNumericDiffCostFunction<ScanResidual, ceres::CENTRAL>(functor);
  cost->AddParameterBlock(static_cast<int>(x.size()));
  cost->SetNumResiduals(static_cast<int>(used.size()));
  ceres::Problem problem;
  problem.AddResidualBlock(cost, new ceres::HuberLoss(1.0), x.data());
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = fit.max_iterations;
  solver.function_tolerance = 1e-10;
  solver.parameter_tolerance = 1e-8;
  solver.logging_type = ceres::SILENT;
  IterationReporter reporter(on_iteration);
  solver.callbacks.push_back(&reporter);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  CheckInterrupt();

  DistortionFitResult result;
  result.points = used.size();
  result.solver.usable = summary.IsSolutionUsable() && std::isfinite(summary.final_cost);
  result.solver.termination = ceres::TerminationTypeToString(summary.termination_type);
  result.solver.message = summary.message;
  result.solver.iterations = static_cast<int>(summary.iterations.size());
  result.solver.initial_cost = summary.initial_cost;
  result.solver.final_cost = summary.final_cost;
  result.solver.seconds = summary.total_time_in_seconds;
  const ScanResidual eval{&grid, &history, &used, &seeds, &undistorted, start, options, fit.free};
  result.params = eval.Params(x.data());
  result.initial_rms_mm = ForwardRms(grid, history, surface, used, start, options);
  if (result.solver.usable) result.rms_mm = ForwardRms(grid, history, surface, used, result.params, options);
  return result;
}

}  // namespace waam::twin
