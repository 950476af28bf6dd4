// Path statistics: passes (arc starts), path elements, lengths and time.
#include "planner/path/tool_path.h"

namespace waam::planner {

PathStats ComputeStats(const Plan& plan) {
  PathStats stats;
  stats.layers = plan.layers.size();
  bool arc_on = false;
  const PathPoint* last = nullptr;  // the previous layer's last point
  for (const LayerPath& layer : plan.layers) {
    std::size_t passes = 0;
    std::size_t elements = 0;
    for (std::size_t i = 0; i < layer.points.size(); ++i) {
      const PathPoint& point = layer.points[i];
      // A layer starts a new pass unless its first move continues the previous layer's (continuous spiral); the
      // travel into it from the previous layer's last point counts as travel.
      if (i == 0 && !(point.weld && last != nullptr)) arc_on = false;
      if (i == 0 && last == nullptr) continue;
      const PathPoint& from = i == 0 ? *last : layer.points[i - 1];
      const double length = (point.p_P - from.p_P).norm();
      if (point.weld) {
        if (!arc_on) ++passes;
        ++elements;
        stats.weld_length_mm += length;
      } else {
        stats.travel_length_mm += length;
      }
      arc_on = point.weld;
    }
    if (!layer.points.empty()) last = &layer.points.back();
    stats.passes += passes;
    stats.passes_per_layer.push_back(passes);
    stats.path_elements += elements;
    stats.path_elements_per_layer.push_back(elements);
  }
  return stats;
}

}  // namespace waam::planner
