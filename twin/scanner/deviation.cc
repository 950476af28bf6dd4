// Deviation of the simulated surface: exposed voxel faces as the scanner's points, signed distance to the target.
#include "twin/scanner/deviation.h"

#include <algorithm>
#include <cmath>

#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "twin/scanner/mesh_distance.h"

namespace waam::twin {

DeviationReport MeasureDeviation(const VoxelGrid& grid, const planner::TriangleMesh& target) {
  const MeshDistance distance(target);
  DeviationReport report;
  const double v = grid.voxel_mm();
  const Eigen::Vector3i dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  // The exposed faces in the grid's order, then their distances in parallel (each point its own slot, so the
  // report and its sums below are the same on any number of threads).
  grid.ForEach([&](const VoxelIndex& idx, const VoxelData&) {
    for (const Eigen::Vector3i& d : dirs) {
      if (grid.Solid(idx + d)) continue;
      SurfaceSample s;
      s.face = d;
      s.p_P = grid.Center(idx) + 0.5 * v * d.cast<double>();
      report.points.push_back(s);
    }
  });
  constexpr std::size_t kChunk = 4096;
  ParallelFor((report.points.size() + kChunk - 1) / kChunk, [&](std::size_t chunk) {
    CheckInterrupt();  // Ctrl-C stays responsive on large parts
    const std::size_t end = std::min(report.points.size(), (chunk + 1) * kChunk);
    for (std::size_t i = chunk * kChunk; i < end; ++i) {
      report.points[i].deviation_mm = distance.SignedDistance(report.points[i].p_P);
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
