// The build's timeline: every move, arc start and end, dwell and wait of a plan laid end to end in time.
#include "planner/timeline/timeline.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/error.h"

namespace waam::planner {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The time and kind of one arc-off move: the samples [begin, end) of `motion` (begin > 0) follow the path from sample
// begin - 1 to the move's end point. The move is parametrised by u in [0, 1] (the samples are evenly spaced in u);
// an axis j whose largest slope along it is D_j = max |dq_j/du| limits u' <= v_j / D_j and u'' <= a_j / D_j, the TCP
// limits u' <= v_tcp / L. The largest such u' and u'' give a rest-to-rest trapezoid over u = 0..1. (The curvature
// term q'' u'^2 of the joint accelerations is left out: it is small on the straight moves between passes.)
struct TravelTiming {
  double time_s = 0.0;
  bool positioner = false;
};

TravelTiming TimeTravelMove(const std::vector<CellSample>& motion, std::size_t begin, std::size_t end, double length_mm,
                            const AxisLimits& limits, double rapid_speed_mm_s) {
  TravelTiming result;
  double speed_u = length_mm > 0.0 ? rapid_speed_mm_s / length_mm : kInf;  // 1/s
  double accel_u = kInf;                                                    // 1/s^2
  int speed_axis = -1;  // the axis that sets the peak speed (-1: the TCP)
  bool positioner_moves = false;
  bool joints_known = true;
  for (std::size_t k = begin - 1; k < end; ++k) joints_known = joints_known && motion[k].reachable;
  if (joints_known && end > begin) {
    const double steps = static_cast<double>(end - begin);
    for (int j = 0; j < 8; ++j) {
      double slope = 0.0;  // D_j, rad per unit u
      for (std::size_t k = begin; k < end; ++k) slope = std::max(slope, std::abs(motion[k].q[j] - motion[k - 1].q[j]));
      slope *= steps;
      if (slope <= 1e-12) continue;
      if (j >= 6) positioner_moves = true;
      if (limits.max_speed[j] / slope < speed_u) speed_u = limits.max_speed[j] / slope, speed_axis = j;
      accel_u = std::min(accel_u, limits.max_accel[j] / slope);
    }
  }
  if (!std::isfinite(speed_u)) return result;  // nothing moves
  result.time_s = TrapezoidTime(1.0, speed_u, accel_u);
  result.positioner = positioner_moves && (length_mm < 1e-6 || speed_axis >= 6);
  return result;
}

// Appends spans and keeps the running clock.
class SpanWriter {
 public:
  explicit SpanWriter(Timeline* timeline) : timeline_(timeline) {}
  void Add(SpanKind kind, double duration_s, int layer, std::size_t point) {
    if (!(duration_s > 0.0)) return;
    timeline_->spans.push_back({kind, now_, now_ + duration_s, layer, point});
    now_ += duration_s;
  }
  double now() const { return now_; }

 private:
  Timeline* timeline_;
  double now_ = 0.0;
};

void CheckSetting(double value, const char* key, bool positive) {
  WAAM_THROW_UNLESS(std::isfinite(value) && (positive ? value > 0.0 : value >= 0.0),
                    "timeline setting " << key << " = " << value << ": must be " << (positive ? "> 0" : ">= 0"));
}

// True when the move to the point after plan.layers[l].points[i] (in this layer or the next that has points) lays a
// bead; false at the plan's end.
bool NextMoveWelds(const Plan& plan, std::size_t l, std::size_t i) {
  if (i + 1 < plan.layers[l].points.size()) return plan.layers[l].points[i + 1].weld;
  for (std::size_t k = l + 1; k < plan.layers.size(); ++k) {
    if (!plan.layers[k].points.empty()) return plan.layers[k].points.front().weld;
  }
  return false;
}

// Layer sums, first arc start and last arc end from the spans.
void SumLayers(const Plan& plan, Timeline* timeline) {
  timeline->layers.assign(plan.layers.size(), LayerTimes{});
  std::vector<bool> has_arc(plan.layers.size(), false);
  for (std::size_t l = 0; l < plan.layers.size(); ++l) timeline->layers[l].layer = plan.layers[l].index;
  std::vector<double> first_span(plan.layers.size(), kInf);
  for (const TimedSpan& span : timeline->spans) {
    LayerTimes& layer = timeline->layers[static_cast<std::size_t>(span.layer)];
    const double d = span.end_s - span.start_s;
    first_span[static_cast<std::size_t>(span.layer)] = std::min(first_span[static_cast<std::size_t>(span.layer)],
                                                                span.start_s);
    switch (span.kind) {
      case SpanKind::kArcOn:
      case SpanKind::kArcStart:
      case SpanKind::kArcEnd:
        layer.arc_on_s += d;
        timeline->arc_on_s += d;
        if (!has_arc[static_cast<std::size_t>(span.layer)]) layer.start_s = span.start_s;
        has_arc[static_cast<std::size_t>(span.layer)] = true;
        layer.end_s = span.end_s;
        break;
      case SpanKind::kTravel:
      case SpanKind::kPositioner:
        layer.travel_s += d;
        timeline->travel_s += d;
        break;
      case SpanKind::kWait:
        layer.wait_s += d;
        timeline->wait_s += d;
        break;
    }
  }
  // A layer without an arc starts and ends where its first span starts (or where the build stands then).
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    if (has_arc[l]) continue;
    const double t = std::isfinite(first_span[l]) ? first_span[l] : (l > 0 ? timeline->layers[l - 1].end_s : 0.0);
    timeline->layers[l].start_s = timeline->layers[l].end_s = t;
  }
  timeline->total_s = timeline->spans.empty() ? 0.0 : timeline->spans.back().end_s;
}

}  // namespace

AxisLimits AxisLimitsOf(const CellKinematics& cell) {
  AxisLimits limits;
  limits.max_speed << cell.arm.max_speed, cell.positioner.tilt_max_speed, cell.positioner.rotation_max_speed;
  limits.max_accel << cell.arm.max_accel, cell.positioner.tilt_max_accel, cell.positioner.rotation_max_accel;
  return limits;
}

TimelineSettings TimelineSettingsOf(const ProcessSettings& process) {
  TimelineSettings settings;
  settings.arc_start_s = process.arc_start_s;
  settings.arc_end_s = process.arc_end_s;
  settings.rapid_speed_mm_s = process.rapid_speed_mm_min / 60.0;
  settings.min_layer_time_s = process.interpass.min_layer_time_s;
  return settings;
}

double TrapezoidTime(double distance, double max_speed, double max_accel) {
  if (!(distance > 0.0)) return 0.0;
  if (!std::isfinite(max_accel)) return distance / max_speed;
  // Accelerating to v and back takes v^2 / a of the distance; a shorter move never reaches v (a triangle).
  if (distance >= max_speed * max_speed / max_accel) return distance / max_speed + max_speed / max_accel;
  return 2.0 * std::sqrt(distance / max_accel);
}

namespace {

// Throws InputError naming the first setting or axis limit that is not finite or out of range.
void CheckTimelineInputs(const AxisLimits& limits, const TimelineSettings& settings) {
  CheckSetting(settings.arc_start_s, "arc_start_s", false);
  CheckSetting(settings.arc_end_s, "arc_end_s", false);
  CheckSetting(settings.rapid_speed_mm_s, "rapid_speed_mm_s", true);
  CheckSetting(settings.min_layer_time_s, "min_layer_time_s", false);
  for (double w : settings.extra_wait_before_layer_s) CheckSetting(w, "extra_wait_before_layer_s", false);
  for (int j = 0; j < 8; ++j) {
    CheckSetting(limits.max_speed[j], "axis max_speed", true);
    CheckSetting(limits.max_accel[j], "axis max_accel", true);
  }
}

// The motion's samples of each point's move: first_sample[g] .. first_sample[g + 1] (g counted over the plan);
// empty without a motion.
std::vector<std::size_t> FirstSampleOfEachPoint(const Plan& plan, const std::vector<CellSample>& motion) {
  std::vector<std::size_t> first_sample;
  if (motion.empty()) return first_sample;
  std::size_t points = 0;
  for (const LayerPath& layer : plan.layers) points += layer.points.size();
  first_sample.assign(points + 1, motion.size());
  for (std::size_t k = motion.size(); k-- > 0;) first_sample[static_cast<std::size_t>(motion[k].point)] = k;
  // The motion must be PlanCellMotion's of this very plan.
  WAAM_DEMAND(static_cast<std::size_t>(motion.back().point) + 1 == points && first_sample[0] == 0);
  return first_sample;
}

}  // namespace

Timeline BuildTimeline(const Plan& plan, const std::vector<CellSample>& motion, const AxisLimits& limits,
                       const TimelineSettings& settings) {
  CheckTimelineInputs(limits, settings);
  const std::vector<std::size_t> first_sample = FirstSampleOfEachPoint(plan, motion);

  Timeline timeline;
  SpanWriter out(&timeline);
  const PathPoint* prev = nullptr;
  int prev_layer = 0;
  std::size_t prev_point = 0;
  bool arc_on = false;         // the last move laid a bead (a pass is open)
  double last_layer_start = -1.0;  // first arc start of the last layer that had one, s
  int last_started_layer = -1;
  std::size_t g = 0;  // the point's index over the whole plan
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    const int layer = static_cast<int>(l);
    const std::vector<PathPoint>& pts = plan.layers[l].points;
    for (std::size_t i = 0; i < pts.size(); ++i, ++g) {
      const PathPoint& p = pts[i];
      if (prev != nullptr) {
        const double length = (p.p_P - prev->p_P).norm();
        if (p.weld) {
          // The layer's first weld move waits out the rest of min_layer_time_s and the extra wait, at the point the
          // torch reached: before the arc start of a new pass, or between the two weld moves of a layer reached with
          // the arc burning (a continuous spiral: a pause with no arc end or start, as the thermal model's interpass
          // wait runs it).
          if (last_started_layer != layer) {
            if (last_started_layer >= 0) {
              out.Add(SpanKind::kWait, settings.min_layer_time_s - (out.now() - last_layer_start), prev_layer,
                      prev_point);
            }
            if (l < settings.extra_wait_before_layer_s.size()) {
              out.Add(SpanKind::kWait, settings.extra_wait_before_layer_s[l], prev_layer, prev_point);
            }
            last_layer_start = out.now();
            last_started_layer = layer;
          }
          if (!arc_on) out.Add(SpanKind::kArcStart, settings.arc_start_s, prev_layer, prev_point);
          if (p.speed_mm_s > 0.0) out.Add(SpanKind::kArcOn, length / p.speed_mm_s, layer, i);
          arc_on = true;
        } else {
          if (arc_on) out.Add(SpanKind::kArcEnd, settings.arc_end_s, prev_layer, prev_point);
          arc_on = false;
          TravelTiming travel;
          if (motion.empty()) {
            travel.time_s = length / settings.rapid_speed_mm_s;
          } else {
            travel = TimeTravelMove(motion, first_sample[g], first_sample[g + 1], length, limits,
                                    settings.rapid_speed_mm_s);
          }
          out.Add(travel.positioner ? SpanKind::kPositioner : SpanKind::kTravel, travel.time_s, layer, i);
        }
      }
      // A dwell where a pass ends (the program switched the arc off, then waited: G-code M5 / M103 then G4, FANUC
      // Arc End then WAIT) comes after the pass's arc end; a dwell between two weld moves is a pause of the open
      // pass.
      if (arc_on && p.dwell_s > 0.0 && !NextMoveWelds(plan, l, i)) {
        out.Add(SpanKind::kArcEnd, settings.arc_end_s, layer, i);
        arc_on = false;
      }
      out.Add(SpanKind::kWait, p.dwell_s, layer, i);
      prev = &p;
      prev_layer = layer;
      prev_point = i;
    }
  }
  if (arc_on) out.Add(SpanKind::kArcEnd, settings.arc_end_s, prev_layer, prev_point);
  SumLayers(plan, &timeline);
  return timeline;
}

}  // namespace waam::planner
