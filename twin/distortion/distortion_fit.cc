// Ceres fit of the inherent-strain parameters to a scan of the distorted part. Derivatives by central differences:
// one distortion solve per parameter and side.
//
// The residual of a scan point s is a point-to-plane distance to the distorted twin surface, sampled at the exposed
// voxel faces of the undistorted deposit (the faces the twin's scan samples; exact at any part size, where a surface
// mesh is coarsened past its facet limit). Its face c is found by pulling s back through the displacement field u:
// c_(k+1) = the face nearest to s - u(c_k), from the face the start parameters move nearest to s, until it repeats (u is evaluated at face
// centres only, so the search never leaves the part even when the part moved farther than its wall is thick, and
// |grad u| << 1 makes it settle in a few steps). The residual is n_c . (s - c - u(c)): zero where the distorted
// surface passes through s, smooth in the parameters for a given face and continuous across a flat wall.
#include "twin/distortion/distortion_fit.h"

#include <algorithm>
#include <cmath>

#include <ceres/ceres.h>

#include "models/core/error.h"
#include "models/core/progress.h"
#include "twin/distortion/voxel_faces.h"

namespace waam::twin {
namespace {

using models::DistortionParam;

// Strains and stiffnesses are fitted as logarithms (positive, and of very different sizes); the exponent as is.
bool LogScale(DistortionParam param) { return param != DistortionParam::kHeatExponent; }

// Steps of the face search (it settles in two or three on the test parts).
constexpr int kPullBackIterations = 8;
// A scan point farther than this from the undistorted part is not of it (mm); a pre-image is searched this far.
constexpr double kSeedReachMm = 50.0;
constexpr double kFaceReachMm = 20.0;

struct ScanResidual {
  const VoxelGrid* grid;
  const DepositHistory* history;
  const std::vector<Eigen::Vector3d>* points;
  const std::vector<int>* seeds;  // per point: the undistorted voxel face nearest to it
  const std::vector<double>* scale;  // per point: sqrt(weight / mean weight), 1 for a point cloud
  const internal::VoxelFaces* faces;
  models::DistortionParams start;
  DistortionOptions options;
  std::vector<DistortionParam> free;

  models::DistortionParams Params(const double* x) const {
    models::DistortionParams p = start;
    for (std::size_t k = 0; k < free.size(); ++k) {
      models::ParamValue(p, free[k]) = LogScale(free[k]) ? std::exp(x[k]) : x[k];
    }
    return p;
  }
  bool operator()(double const* const* x, double* residual) const {
    const models::DistortionParams p = Params(x[0]);
    // Outside the valid range: the residual is not defined there, and Ceres shortens the step.
    if (!models::DistortionParamsProblem(p, "fit").empty()) return false;
    const DistortionField field = ComputeDistortion(*grid, *history, p, options);
    for (std::size_t i = 0; i < points->size(); ++i) {
      const Eigen::Vector3d& s = (*points)[i];
      int c = (*seeds)[i];
      for (int k = 0; k < kPullBackIterations; ++k) {
        const int next = faces->Nearest(s - field.Displacement(faces->centre(c)), kFaceReachMm);
        if (next < 0 || next == c) break;
        c = next;
      }
      residual[i] = (*scale)[i] * faces->PlaneDistance(c, s - field.Displacement(faces->centre(c)));
    }
    return true;
  }
};

// Rms (mm) of the residuals at `x`, 0 when the parameters are invalid.
double ResidualRms(const ScanResidual& residual, const std::vector<double>& x, std::size_t n) {
  std::vector<double> r(n);
  const double* xs[1] = {x.data()};
  if (!residual(xs, r.data())) return 0.0;
  double sum = 0.0;
  for (double v : r) sum += v * v;
  return std::sqrt(sum / std::max<std::size_t>(1, n));
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

void ValidateDistortionFitOptions(const DistortionFitOptions& fit, models::DistortionMode mode) {
  WAAM_THROW_UNLESS(!fit.free.empty(), "distortion fit: no free parameter");
  for (std::size_t k = 0; k < fit.free.size(); ++k) {
    const DistortionParam param = fit.free[k];
    for (std::size_t j = 0; j < k; ++j) {
      WAAM_THROW_UNLESS(fit.free[j] != param,
                        "distortion fit: free parameter '" << NameOf(param) << "' is given twice");
    }
    // The reduced model has no substrate: its stiffness would be a free parameter with a zero Jacobian column.
    WAAM_THROW_UNLESS(!(mode == models::DistortionMode::kReduced && param == DistortionParam::kSubstrateStiffness),
                      "distortion fit: free parameter 'substrate_stiffness_n_mm3' has no effect in mode reduced "
                      "(no substrate compliance): fit it in mode fe");
  }
  WAAM_THROW_UNLESS(fit.max_points >= 10, "distortion fit: max_points = " << fit.max_points << ": must be >= 10");
  WAAM_THROW_UNLESS(fit.max_iterations >= 1 && fit.max_iterations <= 1000,
                    "distortion fit: max_iterations = " << fit.max_iterations << ": must be in [1, 1000]");
}

namespace {

// Throws InputError for invalid start parameters or options, fewer than 10 scan points or a weight that is not a
// positive number (one per point, or none).
void ValidateFitInputs(const std::vector<Eigen::Vector3d>& scan, const models::DistortionParams& start,
                       const DistortionOptions& options, const DistortionFitOptions& fit,
                       const std::vector<double>& scan_weight) {
  models::ValidateDistortionParams(start, "distortion fit start");
  ValidateDistortionOptions(options);
  ValidateDistortionFitOptions(fit, options.mode);
  WAAM_THROW_UNLESS(scan.size() >= 10, "distortion fit: the scan has " << scan.size() << " points: need >= 10");
  WAAM_THROW_UNLESS(scan_weight.empty() || scan_weight.size() == scan.size(),
                    "distortion fit: " << scan_weight.size() << " weights for " << scan.size() << " scan points");
  for (std::size_t i = 0; i < scan_weight.size(); ++i) {
    WAAM_THROW_UNLESS(scan_weight[i] > 0.0 && std::isfinite(scan_weight[i]),
                      "distortion fit: scan point " << i << " has weight " << scan_weight[i] << ": must be > 0");
  }
}

// The scan points the fit uses: every k-th (at most fit.max_points), each with its seed face and the square root of
// its weight per mean weight.
struct FitPoints {
  std::vector<Eigen::Vector3d> used;
  std::vector<int> seeds;
  std::vector<double> scale;
};

// Points nowhere near the part are left out (and counted); throws InputError when fewer than 10 remain or more are
// far than near. Seeds: the face whose centre the start parameters move nearest to the scan point, so that the face
// search starts next to its answer (from the undistorted faces it can settle on a wrong face where the part moved by
// centimetres).
FitPoints PickFitPoints(const VoxelGrid& grid, const DepositHistory& history, const internal::VoxelFaces& faces,
                        const std::vector<Eigen::Vector3d>& scan, const models::DistortionParams& start,
                        const DistortionOptions& options, const DistortionFitOptions& fit,
                        const std::vector<double>& scan_weight) {
  FitPoints points;
  std::size_t far = 0;
  const DistortionField start_field = ComputeDistortion(grid, history, start, options);
  const internal::VoxelFaces moved =
      faces.Moved([&](const Eigen::Vector3d& c) { return start_field.Displacement(c); });
  const std::size_t step = std::max<std::size_t>(1, scan.size() / fit.max_points);
  for (std::size_t i = 0; i < scan.size(); i += step) {
    const int f = moved.Nearest(scan[i], kSeedReachMm);
    if (f < 0) {
      ++far;
      continue;
    }
    points.used.push_back(scan[i]);
    points.seeds.push_back(f);
    points.scale.push_back(scan_weight.empty() ? 1.0 : scan_weight[i]);
  }
  const std::size_t n = points.used.size();
  WAAM_THROW_UNLESS(n >= 10 && far <= n,
                    "distortion fit: " << far << " of " << far + n << " scan points are farther than "
                    << kSeedReachMm << " mm from the twin part: the scan must be of this part, in its part frame (mm)");
  // Least squares of sqrt(w / mean w) r: the sum of w r^2 per unit weight, the rms per unit area on an STL.
  double mean_weight = 0.0;
  for (const double w : points.scale) mean_weight += w / static_cast<double>(points.scale.size());
  for (double& w : points.scale) w = std::sqrt(w / mean_weight);
  return points;
}

// Robust (Huber) least squares of `residual` over x, from x (updated in place); the solve stops on Ctrl-C.
ceres::Solver::Summary SolveFit(const ScanResidual& residual, std::size_t residuals, int max_iterations,
                                const std::function<void(int)>& on_iteration, std::vector<double>& x) {
  auto* cost = new ceres::DynamicNumericDiffCostFunction<ScanResidual, ceres::CENTRAL>(new ScanResidual(residual));
  cost->AddParameterBlock(static_cast<int>(x.size()));
  cost->SetNumResiduals(static_cast<int>(residuals));
  ceres::Problem problem;
  problem.AddResidualBlock(cost, new ceres::HuberLoss(1.0), x.data());
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = max_iterations;
  solver.function_tolerance = 1e-10;
  solver.parameter_tolerance = 1e-8;
  solver.logging_type = ceres::SILENT;
  IterationReporter reporter(on_iteration);
  solver.callbacks.push_back(&reporter);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  CheckInterrupt();
  return summary;
}

}  // namespace

DistortionFitResult FitDistortion(const VoxelGrid& grid, const DepositHistory& history,
                                  const std::vector<Eigen::Vector3d>& scan, const models::DistortionParams& start,
                                  const DistortionOptions& options, const DistortionFitOptions& fit,
                                  const std::function<void(int)>& on_iteration, const std::vector<double>& scan_weight) {
  ValidateFitInputs(scan, start, options, fit, scan_weight);
  const internal::VoxelFaces faces(grid);
  WAAM_THROW_UNLESS(faces.size() > 0, "distortion fit: the deposit is empty");
  const FitPoints points = PickFitPoints(grid, history, faces, scan, start, options, fit, scan_weight);
  const ScanResidual eval{&grid, &history, &points.used, &points.seeds, &points.scale, &faces, start, options, fit.free};
  std::vector<double> x(fit.free.size());
  for (std::size_t k = 0; k < fit.free.size(); ++k) {
    models::DistortionParams p = start;
    const double v = models::ParamValue(p, fit.free[k]);
    x[k] = LogScale(fit.free[k]) ? std::log(std::max(v, 1e-12)) : v;
  }
  const std::vector<double> x0 = x;
  const ceres::Solver::Summary summary = SolveFit(eval, points.used.size(), fit.max_iterations, on_iteration, x);

  DistortionFitResult result;
  result.points = points.used.size();
  result.solver.usable = summary.IsSolutionUsable() && std::isfinite(summary.final_cost);
  result.solver.termination = models::TerminationNamed(ceres::TerminationTypeToString(summary.termination_type));
  result.solver.message = summary.message;
  result.solver.iterations = static_cast<int>(summary.iterations.size());
  result.solver.initial_cost = summary.initial_cost;
  result.solver.final_cost = summary.final_cost;
  result.solver.seconds = summary.total_time_in_seconds;
  result.params = eval.Params(x.data());
  result.initial_rms_mm = ResidualRms(eval, x0, points.used.size());
  if (result.solver.usable) result.rms_mm = ResidualRms(eval, x, points.used.size());
  return result;
}

}  // namespace waam::twin
