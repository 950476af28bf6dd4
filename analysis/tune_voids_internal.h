// Internal pieces of `waam tune-voids`: the cropped trial plan and its simulation and measures.
#pragma once

#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "analysis/tune_voids_command.h"
#include "planner/path/tool_path.h"
#include "planner/path/void_filling.h"
#include "twin/simulation_settings.h"

namespace waam::analysis::internal {

// The square simulated around a junction and the radius within which voids and peaks count as the junction's.
struct JunctionCrop {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // mm
  double half_mm = 0.0;                              // half-size of the square, mm
  double reach_mm = 0.0;                             // radius around the centre, mm
};

// The first `layers` layers of `base` with `filler` applied, clipped to the crop: each piece of weld path inside the
// square becomes a pass (its arc starts and stops lie at the crop edge, away from the junction).
planner::Plan TrialPlan(const planner::Plan& base, int layers, const planner::VoidFiller& filler,
                        const JunctionCrop& crop);

// Deposits `plan` and measures the junction (see TuneTrial); writes a PNG section at mid-height to `picture` when
// it is not empty. Throws InputError for invalid simulation settings.
TuneTrial SimulateTrial(const planner::Plan& plan, const twin::SimulationSettings& settings,
                        double rapid_speed_mm_s, const JunctionCrop& crop, const std::filesystem::path& picture);

}  // namespace waam::analysis::internal
