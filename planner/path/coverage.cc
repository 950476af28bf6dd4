// Uncovered slice area: the slice minus the weld moves buffered by half their bead width, in the slice plane.
#include "planner/path/coverage.h"

#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "planner/geometry/clipper_adapter.h"
#include "planner/geometry/polygon.h"

namespace waam::planner {

double UncoveredArea(const LayerPath& layer) {
  if (!layer.slice_in_plane) return std::numeric_limits<double>::quiet_NaN();
  if (layer.slice.empty()) return 0.0;
  // Moves grouped by bead width (0.05 mm bins; a CSW plan varies it point by point), each group buffered once.
  constexpr double kWidthBinMm = 0.05;
  std::map<long, std::vector<internal::Polyline>> by_width;
  for (std::size_t i = 1; i < layer.points.size(); ++i) {
    const PathPoint& p = layer.points[i];
    if (!p.weld || p.bead_width_mm <= 0.0) continue;
    const Eigen::Vector2d a = layer.slice_axes_P.transpose() * (layer.points[i - 1].p_P - layer.slice_origin_P);
    const Eigen::Vector2d b = layer.slice_axes_P.transpose() * (p.p_P - layer.slice_origin_P);
    by_width[std::lround(p.bead_width_mm / kWidthBinMm)].push_back({a, b});
  }
  std::vector<PolygonWithHoles> covered;
  for (const auto& [bin, moves] : by_width) {
    const std::vector<PolygonWithHoles> swept = internal::BufferPolylines(moves, 0.5 * bin * kWidthBinMm);
    covered.insert(covered.end(), swept.begin(), swept.end());
  }
  return Area(internal::Difference(layer.slice, covered));
}

}  // namespace waam::planner
