// Ceres fit of the inherent-strain parameters: each residual is the distance of a scan point to the predicted
// distorted surface (the deposit's surface mesh with every vertex moved by the displacement field). Derivatives by
// central differences: one distortion solve per parameter and side.
#include "twin/distortion/distortion_fit.h"

#include <algorithm>
#include <cmath>

#include <ceres/ceres.h>

#include "models/core/error.h"
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

struct ScanResidual {
  const VoxelGrid* grid;
  const DepositHistory* history;
  const std::vector<Eigen::Vector3d>* points;
  const planner::TriangleMesh* surface;
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
    planner::TriangleMesh moved = *surface;
    for (Eigen::Vector3d& v : moved.vertices) v += field.Displacement(v);
    const MeshDistance distance(moved);
    for (std::size_t i = 0; i < points->size(); ++i) residual[i] = distance.SignedDistance((*points)[i]);
    return true;
  }
};

}  // namespace

DistortionFitResult FitDistortion(const VoxelGrid& grid, const DepositHistory& history,
                                  const std::vector<Eigen::Vector3d>& scan, const models::DistortionParams& start,
                                  const DistortionOptions& options, const DistortionFitOptions& fit) {
  models::ValidateDistortionParams(start, "distortion fit start");
  ValidateDistortionOptions(options);
  WAAM_THROW_UNLESS(!fit.free.empty(), "distortion fit: no free parameter");
  for (const std::string& name : fit.free) {
    models::DistortionParams probe;
    WAAM_THROW_UNLESS(Field(&probe, name) != nullptr,
                      "distortion fit: free parameter '" << name << "': must be one of strain, heat_exponent, "
                      "vertical_ratio, substrate_stiffness_n_mm3");
  }
  WAAM_THROW_UNLESS(fit.max_points >= 10, "distortion fit: max_points = " << fit.max_points << ": must be >= 10");
  WAAM_THROW_UNLESS(scan.size() >= 10, "distortion fit: the scan has " << scan.size() << " points: need >= 10");
  std::vector<Eigen::Vector3d> used;
  const std::size_t step = std::max<std::size_t>(1, scan.size() / fit.max_points);
  for (std::size_t i = 0; i < scan.size(); i += step) used.push_back(scan[i]);
  const planner::TriangleMesh surface = ExtractSurface(grid);

  auto* functor = new ScanResidual{&grid, &history, &used, &surface, start, options, fit.free};
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
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);

  DistortionFitResult result;
  result.points = used.size();
  result.solver.usable = summary.IsSolutionUsable() && std::isfinite(summary.final_cost);
  result.solver.termination = ceres::TerminationTypeToString(summary.termination_type);
  result.solver.message = summary.message;
  result.solver.iterations = static_cast<int>(summary.iterations.size());
  result.solver.initial_cost = summary.initial_cost;
  result.solver.final_cost = summary.final_cost;
  result.solver.seconds = summary.total_time_in_seconds;
  ScanResidual eval{&grid, &history, &used, &surface, start, options, fit.free};
  result.params = eval.Params(x.data());
  std::vector<double> r(used.size());
  const double* xs[1] = {x.data()};
  if (eval(xs, r.data())) {
    double sum = 0.0;
    for (double v : r) sum += v * v;
    result.rms_mm = std::sqrt(sum / std::max<std::size_t>(1, r.size()));
  }
  return result;
}

}  // namespace waam::twin
