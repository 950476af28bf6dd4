// The deposition twin's scanner: measures a deposited part like the papers measured theirs.
#pragma once

#include <cstddef>
#include <string>

#include "planner/mesh/triangle_mesh.h"
#include "planner/path/tool_path.h"
#include "twin/simulation_settings.h"
#include "twin/deposition/bead_deposition.h"
#include "twin/scanner/deviation.h"
#include "twin/scanner/surface_metrics.h"
#include "twin/scanner/voids.h"

namespace waam::twin {

// The measures `waam simulate` reports (simulate.json).
struct TwinMeasures {
  double voxel_mm = 0.0;
  std::size_t layers = 0;
  std::size_t beads = 0;                 // weld passes (arc starts)
  std::size_t voxels = 0;                // occupied voxels
  double weld_length_mm = 0.0;           // executed (blended) path length
  double build_time_s = 0.0;             // weld and travel time of the executed path
  double deposited_volume_mm3 = 0.0;     // occupied voxels x voxel volume
  double expected_volume_mm3 = 0.0;      // sum of bead section area x length (start/stop shapes included)
  double waviness_mm = 0.0;              // largest peak-to-valley along the x and y section lines of the top layer
  double ra_mm = 0.0;                    // Ding eq. 7 over the top layer region (w/2 in from its outline)
  // Ding Fig. 13 (surface variation): mean, lowest and highest top height over the same columns as ra_mm, mm; NaN
  // when the region has no column w/2 in from its outline.
  double top_mean_mm = 0.0;
  double top_min_mm = 0.0;
  double top_max_mm = 0.0;
  BoundaryLag boundary_lag;              // 003 Fig. 24 measure along the x and y section lines of the top layer
  // Why the top-surface measures above (waviness, Ra, top height, boundary lag) do not apply to this part, e.g. a
  // multi-directional or non-planar build; empty when they apply. When set, those measures are NaN.
  std::string top_surface_not_applicable;
  std::size_t grid_memory_bytes = 0;
  double deposition_s = 0.0;             // wall-clock time of the deposition alone, s
};

// Why the top-surface measures of a planar build (Ra, waviness, top height, boundary lag: measured on the top
// layer's region from above) do not apply to `plan`, or "" when they do. They do not apply when a layer grows along
// a direction more than 1 deg from +z (multi-directional), when a layer is not a horizontal plane (a curved,
// tilted or developed slice, or weld points of one layer spanning more than 1.5 bead heights in z), or when the top
// layer has no sliced region (an imported program).
std::string TopSurfaceNotApplicable(const planner::Plan& plan);

// Everything the twin produces in memory.
struct TwinResult {
  Depositor depositor;
  HeightMap top;
  DeviationReport deviation;             // empty when no target mesh was given
  VoidReport voids;
  TwinMeasures measures;
};

// The virtual scanner over a deposited build: measures the part `depositor` holds (deposited from `plan` by
// DepositPlan, which it takes over) against `target` (may be null: then the target volume is the planned layer regions
// extruded and no surface deviation is measured). `bead_width_mm` (> 0) sets the margins of the surface measures.
// Throws InputError for a bead width <= 0 or a target volume past the voxel limit.
TwinResult MeasureBuild(const planner::Plan& plan, Depositor depositor, const planner::TriangleMesh* target,
                        double bead_width_mm);

}  // namespace waam::twin
