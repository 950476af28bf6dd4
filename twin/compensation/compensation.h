// The offline compensation loop of 003 sec. 6.5.2 run against the twin: deposit, distort, scan, move every reference
// point of the tool path against the measured deviation (r*_i = r_i - S_i), repeat.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "models/distortion/distortion_params.h"
#include "planner/mesh/triangle_mesh.h"
#include "planner/path/tool_path.h"
#include "twin/simulation_settings.h"
#include "twin/deposition/heat_bead.h"
#include "twin/distortion/distortion.h"
#include "twin/scanner/scan_deviation.h"

#include "models/core/enum_names.h"

namespace waam::twin {

// What the scans are compared with: twin (the undistorted deposit of the nominal path) or target (the mesh).
enum class CompensationReference { kTwin, kTarget };
constexpr std::array<EnumName<CompensationReference>, 2> EnumNames(CompensationReference) {
  return {{{CompensationReference::kTwin, "twin"}, {CompensationReference::kTarget, "target"}}};
}
WAAM_ENUM_JSON(CompensationReference)
// How S_i is estimated: axis (central-axis offset + per-point cross section) or points (per point only).
enum class CorrectionMethod { kAxis, kPoints };
constexpr std::array<EnumName<CorrectionMethod>, 2> EnumNames(CorrectionMethod) {
  return {{{CorrectionMethod::kAxis, "axis"}, {CorrectionMethod::kPoints, "points"}}};
}
WAAM_ENUM_JSON(CorrectionMethod)

struct CompensationOptions {
  int max_iterations = 3;            // compensated builds after the first (uncompensated) one, >= 0
  double tolerance_mm = 0.0;         // stop when max |deviation| < tolerance; 0 = the simulated part's max waviness
  double reference_spacing_mm = 2.0; // reference points of the tool path at most this far apart, mm (003: 2 mm)
  double axis_step_mm = 2.0;         // central-axis station spacing, mm
  double rapid_speed_mm_s = 100.0;   // arc-off travel speed, mm/s
  double wire_feed_mm_s = 53.3;      // process wire feed, mm/s (heat input)
  double bead_width_mm = 6.0;        // planned bead width, mm (scan neighbourhood and waviness margin)
  models::DistortionParams params;
  DistortionOptions distortion;
  CompensationReference reference = CompensationReference::kTwin;
  CorrectionMethod correction = CorrectionMethod::kAxis;
  std::vector<Eigen::Vector3d> first_scan;  // a real scan of the first part (part frame, mm); empty = simulate it
  std::vector<double> first_scan_weight;    // what each first_scan point counts for (area of a sampled STL); empty = 1
  // Heat into shape (docs/compensation.md): per plan layer, factors on the bead height and width every build lays
  // (the twin reference keeps the planned beads). Empty = the planned beads. distortion.layer_heat drives the
  // strains by the same thermal history.
  BeadHeatFactors bead_heat;
  // Diagnostics on stderr: 0 none, 1 the waviness, top band and correction error every tenth layer, 2 every layer.
  int debug_level = 0;
};

// One build of the loop and what the scan of it showed.
struct CompensationIteration {
  double max_abs_deviation_mm = 0.0;
  double rms_deviation_mm = 0.0;
  double p99_abs_deviation_mm = 0.0; // 99th percentile of |deviation| (by area for a sampled STL scan): the bulk,
                                     // without a few local spots, mm
  double min_deviation_mm = 0.0;
  double max_deviation_mm = 0.0;
  double axis_deviation_mm = 0.0;    // largest central-axis offset from the reference's axis (twin part or target)
  double ovality_pct = 0.0;          // eq. 6.5 at the highest complete section (top cut of Fig. 69)
  double max_abs_vs_target_mm = 0.0; // the same scan against the target mesh (bead-shape errors included)
  double rms_vs_target_mm = 0.0;
  double max_correction_mm = 0.0;    // largest |S_i| applied to the next tool path
  double top_band_mm = 0.0;          // rim below the planned top left out: 2 bead heights + measured shortening, mm
  bool real_scan = false;            // the scan came from a file, not the twin
  // Diagnostic only (the loop never uses it): largest in-plane difference between S_i and the error the twin's
  // hidden displacement field gives at the same point, (r_i + u(r_i) - r0_i)_perp, mm; 0 when not computed.
  double twin_correction_error_mm = 0.0;
  DistortionStats distortion;
};

struct CompensationResult {
  std::vector<CompensationIteration> iterations;  // [0] = uncompensated (or the real scan)
  bool converged = false;
  std::string status;                // converged | max_iterations | diverging
  std::string message;               // one line for the user
  double tolerance_mm = 0.0;
  CompensationReference reference = CompensationReference::kTwin;  // what the deviations are measured against
  double waviness_mm = 0.0;          // maximum side-wall W_t of the undistorted twin part (99th pct. of 4 mm cells), mm
  double waviness_median_mm = 0.0;   // its typical W_t (median of the cells), mm
  double top_band_mm = 0.0;          // two bead heights of the last layer: the least top rim left out, mm
  planner::Plan plan;                // the last compensated tool path (the nominal one resampled if none)
  ScanDeviation first_scan;          // scan of the first build
  ScanDeviation last_scan;           // scan of the last build
};

// Resamples every weld move of `plan` so that reference points are at most `spacing_mm` (> 0) apart.
planner::Plan ResamplePlan(const planner::Plan& plan, double spacing_mm);

// Runs the loop on `plan` (already planned) against `target`. `on_iteration(i, iteration)` may be empty.
// Throws InputError for invalid options or parameters.
CompensationResult Compensate(const planner::Plan& plan, const planner::TriangleMesh& target,
                              const twin::SimulationSettings& settings, const CompensationOptions& options,
                              const std::function<void(int, const CompensationIteration&)>& on_iteration = {});

// The twin's scan of a distorted part: every exposed voxel face centre moved by the displacement field, mm.
std::vector<Eigen::Vector3d> ScanDistortedPart(const VoxelGrid& grid, const DistortionField& field);

}  // namespace waam::twin
