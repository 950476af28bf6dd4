// Deviation of the simulated surface: exposed voxel faces as the scanner's points, signed distance to the target.
#include "twin/scanner/deviation.h"

#include <algorithm>
#include <cmath>

#include "models/core/progress.h"
#include "twin/scanner/mesh_distance.h"

namespace waam::twin {

DeviationReport MeasureDeviation(const VoxelGrid& grid, const planner::TriangleMesh& target) {
  const MeshDistance distance(target);
  DeviationReport report;
  const double v = grid.voxel_mm();
  const Eigen::Vector3i dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::size_t visited = 0;
  grid.ForEach([&](const VoxelIndex& idx, const VoxelData&) {
    if (++visited % 4096 == 0) CheckInterrupt();  // Ctrl-C stays responsive on large parts
    for (const Eigen::Vector3i& d : dirs) {
      if (grid.Solid(idx + d)) continue;
      SurfaceSample s;
      s.face = d;
      s.p_P = grid.Center(idx) + 0.5 * v * d.cast<double>();
      s.deviation_mm = distance.SignedDistance(s.p_P);
      report.points.push_back(s);
    }
  });
  report.samples = report.points.size();
  if (report.samples == 0) return report;
  report.min_mm = report.max_mm = report.points.front().deviation_mm;
  double sum = 0.0, sum2 = 0.0;
  for (const SurfaceSample& s : report.points) {
    report.min_mm = std::min(report.min_mm, s.deviation_mm);
    report.max_mm = std::max(report.max_mm, s.deviation_mm);
    sum += s.deviation_mm;
    sum2 += s.deviation_mm * s.deviation_mm;
  }
  report.mean_mm = sum / report.samples;
  report.rms_mm = std::sqrt(sum2 / report.samples);
  return report;
}

}  // namespace waam::twin
