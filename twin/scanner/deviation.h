// Signed surface deviation of the simulated part from the target mesh, like a scan-to-CAD comparison.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "planner/mesh/triangle_mesh.h"
#include "twin/deposition/voxel_grid.h"

namespace waam::twin {

// One scanned surface point of the simulated part and its signed deviation.
struct SurfaceSample {
  Eigen::Vector3d p_P = Eigen::Vector3d::Zero();  // centre of an exposed voxel face, mm
  Eigen::Vector3i face = Eigen::Vector3i::Zero(); // outward face direction (a unit grid axis)
  double deviation_mm = 0.0;                      // + material outside the target (excess), - inside (shortfall)
};

struct DeviationReport {
  std::size_t samples = 0;
  double min_mm = 0.0;
  double max_mm = 0.0;
  double mean_mm = 0.0;
  double rms_mm = 0.0;
  std::vector<SurfaceSample> points;   // every exposed face (kept for the deviation map)
};

// Scans every exposed face of the deposited part (faces against the substrate are not exposed) and measures its
// signed distance to `target`. Throws InputError for an empty mesh.
DeviationReport MeasureDeviation(const VoxelGrid& grid, const planner::TriangleMesh& target);

}  // namespace waam::twin
