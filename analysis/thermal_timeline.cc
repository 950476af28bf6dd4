// The thermal run's timeline without the cell (weld moves at their speed, 0.5 s arc start, 0.3 s arc end, arc-off
// moves at 100 mm/s): the interim builder until planner::BuildTimeline on the cell is merged (see docs/THERMAL.md).
#include "analysis/thermal_command.h"
namespace waam::analysis {
TimelineBuilder TimelineBuilderFor(const Scenario&, const planner::Plan& plan) {
  return [&plan](const std::vector<double>& extra) {
  planner::Timeline t;
  double now = 0.0;
  auto add = [&](planner::SpanKind kind, double seconds, int layer, std::size_t point) {
    if (seconds <= 0.0) return;
    t.spans.push_back({kind, now, now + seconds, layer, point});
    planner::LayerTimes& l = t.layers[layer];
    (kind == planner::SpanKind::kWait ? l.wait_s : kind == planner::SpanKind::kTravel ? l.travel_s : l.arc_on_s) += seconds;
    now += seconds;
  };
  t.layers.resize(plan.layers.size());
  for (std::size_t li = 0; li < plan.layers.size(); ++li) {
    const planner::LayerPath& layer = plan.layers[li];
    const int l = static_cast<int>(li);
    t.layers[li].layer = l;
    bool first = true;
    for (std::size_t i = 1; i < layer.points.size(); ++i) {
      const planner::PathPoint& p = layer.points[i];
      const double length = (p.p_P - layer.points[i - 1].p_P).norm();
      if (!p.weld) { add(planner::SpanKind::kTravel, length / 100.0, l, i); continue; }
      if (!layer.points[i - 1].weld || i == 1) {
        if (first && li < extra.size()) add(planner::SpanKind::kWait, extra[li], l, i - 1);
        if (first) t.layers[li].start_s = now;
        first = false;
        add(planner::SpanKind::kArcStart, 0.5, l, i - 1);
      }
      add(planner::SpanKind::kArcOn, length / p.speed_mm_s, l, i);
      if (i + 1 == layer.points.size() || !layer.points[i + 1].weld) { add(planner::SpanKind::kArcEnd, 0.3, l, i); t.layers[li].end_s = now; }
    }
  }
  for (const planner::LayerTimes& l : t.layers) { t.arc_on_s += l.arc_on_s; t.travel_s += l.travel_s; t.wait_s += l.wait_s; }
  t.total_s = now;
  return t;
  };
}
}
