// Internal to the models library (includes Ceres): solving a least-squares problem into a SolverReport.
#pragma once

#include <ceres/ceres.h>

#include "models/fit/fit_stats.h"

namespace waam::models::internal {

// Levenberg-Marquardt with dense QR, quiet, single-threaded: the setting every small fit here uses.
ceres::Solver::Options DefaultSolverOptions(int max_iterations = 200);

// Solves `problem` and copies the summary into a SolverReport (usable = IsSolutionUsable() and finite cost).
SolverReport Solve(const ceres::Solver::Options& options, ceres::Problem* problem);

}  // namespace waam::models::internal
