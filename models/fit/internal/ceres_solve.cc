// Runs Ceres and condenses its Summary.
#include "models/fit/internal/ceres_solve.h"

#include <chrono>
#include <cmath>

namespace waam::models::internal {

ceres::Solver::Options DefaultSolverOptions(int max_iterations) {
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.dense_linear_algebra_library_type = ceres::EIGEN;  // no BLAS threads
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-12;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-12;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  return options;
}

SolverReport Solve(const ceres::Solver::Options& options, ceres::Problem* problem) {
  ceres::Solver::Summary summary;
  const auto start = std::chrono::steady_clock::now();
  ceres::Solve(options, problem, &summary);
  SolverReport report;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report.usable = summary.IsSolutionUsable() && std::isfinite(summary.final_cost);
  report.termination = TerminationNamed(ceres::TerminationTypeToString(summary.termination_type));
  report.message = summary.message;
  report.iterations = static_cast<int>(summary.iterations.size());
  report.initial_cost = summary.initial_cost;
  report.final_cost = summary.final_cost;
  if (!std::isfinite(summary.final_cost)) report.message += " (final cost is not finite)";
  return report;
}

}  // namespace waam::models::internal
