// Fitting the distortion parameters with Ceres to a measured scan of the distorted part (real or twin-generated).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "models/distortion/distortion_params.h"
#include "models/fit/fit_stats.h"
#include "twin/deposition/voxel_grid.h"
#include "twin/distortion/deposit_history.h"
#include "twin/distortion/distortion.h"

namespace waam::twin {

struct DistortionFitOptions {
  std::vector<models::DistortionParam> free = {models::DistortionParam::kStrain,
                                              models::DistortionParam::kHeatExponent};  // each at most once
  std::size_t max_points = 3000;   // scan points used (every k-th point, deterministic), >= 10
  int max_iterations = 30;         // Ceres iterations, in [1, 1000]
};

// Throws InputError naming the option for no or a repeated free parameter, one that has no effect in distortion
// mode `mode` (substrate_stiffness_n_mm3 in reduced mode), max_points < 10 or max_iterations outside [1, 1000].
void ValidateDistortionFitOptions(const DistortionFitOptions& fit, models::DistortionMode mode);

struct DistortionFitResult {
  models::DistortionParams params;   // the start with the free parameters replaced by the fit
  models::SolverReport solver;
  double initial_rms_mm = 0.0;       // rms distance of the used scan points to the distorted surface at the start
                                     // (weighted as the fit is), mm
  double rms_mm = 0.0;               // the same to the fitted distorted surface, mm
  std::size_t points = 0;
};

// Fits the free parameters of `start` so that the twin's distorted surface of `grid` (deposited as `history` says)
// passes through the `scan` points (part frame, mm): residual = distance of each scan point, pulled back through the
// displacement field, to the deposit's surface (zero where the moved surface passes through it). Throws InputError
// for invalid fit options (ValidateDistortionFitOptions), too few points or invalid start parameters; a fit that
// fails comes back with solver.usable = false.
// `on_iteration(i)` (may be empty) is called after every Ceres iteration; a Ctrl-C stops the solve and throws
// waam::Interrupted. `scan_weight` (empty: 1 each; else one per scan point, > 0) is what each point counts for, the
// area it stands for on a sampled STL: each residual is scaled by sqrt(weight / mean weight of the used points), so
// the fit and initial_rms_mm / rms_mm are per unit area. Throws InputError for a weight count that is not the point
// count or a weight that is not > 0.
DistortionFitResult FitDistortion(const VoxelGrid& grid, const DepositHistory& history,
                                  const std::vector<Eigen::Vector3d>& scan, const models::DistortionParams& start,
                                  const DistortionOptions& options, const DistortionFitOptions& fit,
                                  const std::function<void(int)>& on_iteration = {},
                                  const std::vector<double>& scan_weight = {});

}  // namespace waam::twin
