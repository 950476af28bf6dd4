// The build's timeline: every second of a plan from the first arc start to the last arc end, split into arc on,
// arc start/end, travel, positioner moves and waits (issue "Time and heat", part 1).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "planner/kinematics/cell_motion.h"
#include "planner/path/tool_path.h"
#include "planner/scenario/scenario.h"

namespace waam::planner {

// What the build does during one span of time.
enum class SpanKind {
  kArcOn,       // welding along a weld move (path length over the planned speed)
  kArcStart,    // ignition before the first weld move of a pass (process.arc_start_s)
  kArcEnd,      // crater fill after the last weld move of a pass (process.arc_end_s)
  kTravel,      // an arc-off move of the torch (trapezoidal joint profile)
  kPositioner,  // the positioner turning while the torch waits
  kWait,        // a dwell: a program's own wait, or an interpass wait
};

// One span of the build's time. Spans are contiguous and in time order.
struct TimedSpan {
  SpanKind kind = SpanKind::kArcOn;
  double start_s = 0.0;   // s from the program's start
  double end_s = 0.0;     // s from the program's start
  int layer = 0;          // index into Plan::layers
  // The point of plan.layers[layer].points the span belongs to: for kArcOn and kTravel the point the move ends at
  // (it starts at point - 1); for the others the point where the torch stands.
  std::size_t point = 0;
};

// Where one layer's time goes. start_s is the layer's first arc start and end_s its last arc end (s from the
// program's start); the sums count the spans of the layer (waits before its first arc start included).
struct LayerTimes {
  int layer = 0;
  double start_s = 0.0;
  double end_s = 0.0;
  double arc_on_s = 0.0;   // arc on, arc start and arc end
  double travel_s = 0.0;   // travel and positioner moves
  double wait_s = 0.0;     // dwells and interpass waits
};

// The timeline of a whole plan: total_s = arc_on_s + travel_s + wait_s.
struct Timeline {
  std::vector<TimedSpan> spans;
  std::vector<LayerTimes> layers;  // one per plan layer, in plan order
  double total_s = 0.0;
  double arc_on_s = 0.0;
  double travel_s = 0.0;
  double wait_s = 0.0;
};

// The speed and acceleration limits of the cell's eight axes (j1..j6 of the arm, positioner tilt, positioner
// rotation), rad/s and rad/s^2, all > 0.
struct AxisLimits {
  Joints8 max_speed = Joints8::Constant(1.0);
  Joints8 max_accel = Joints8::Constant(4.0);
};

// The limits CellKinematics carries (OpwArm::max_speed / max_accel, Positioner::*_max_speed / *_max_accel).
AxisLimits AxisLimitsOf(const CellKinematics& cell);

// What the timeline adds to the planned moves (docs/TIMELINE.md lists the keys, defaults and their sources).
struct TimelineSettings {
  double arc_start_s = 0.5;         // >= 0: ignition before each pass's first weld move (process.arc_start_s), s
  double arc_end_s = 0.3;           // >= 0: crater fill and arc off after each pass (process.arc_end_s), s
  double rapid_speed_mm_s = 100.0;  // > 0: programmed TCP speed of arc-off moves (process.rapid_speed_mm_min), mm/s
  // >= 0: a layer lasts at least this long from its first arc start to the next layer's first arc start; the rest is
  // a wait before the next layer's first arc start (process.interpass.min_layer_time_s), s.
  double min_layer_time_s = 0.0;
  // Per plan layer (may be shorter than the plan; missing entries are 0): a further wait before the layer's first arc
  // start, on top of the min_layer_time_s wait (the thermal model's interpass waits), s >= 0.
  std::vector<double> extra_wait_before_layer_s;
};

// The scenario's process keys of the timeline (arc_start_s, arc_end_s, rapid_speed_mm_min, interpass).
TimelineSettings TimelineSettingsOf(const ProcessSettings& process);

// Time of a rest-to-rest move over `distance` (> 0) with a trapezoidal speed profile: peak speed `max_speed` (> 0),
// acceleration and deceleration `max_accel` (> 0; infinite: a rectangle). Units: any length unit L, L/s, L/s^2;
// returns s. distance >= v^2/a: d/v + v/a; shorter: 2 sqrt(d/a) (a triangle). Throws nothing; 0 for distance <= 0.
double TrapezoidTime(double distance, double max_speed, double max_accel);

// The timeline of `plan`. `motion` is the cell's motion along the plan (PlanCellMotion with the same plan; empty: no
// cell, arc-off moves then run at rapid_speed_mm_s without acceleration limits). Weld moves take their length over
// their planned speed; each pass gets an arc start before its first weld move and an arc end after its last; each
// arc-off move is one rest-to-rest trapezoidal move along its path whose peak speed and acceleration are the largest
// the TCP speed and every axis's limits allow along it (a kPositioner span when a positioner axis sets its time, else
// kTravel); a point's dwell_s is a wait; min_layer_time_s and extra_wait_before_layer_s add waits before a layer's
// first arc start (a layer reached with the arc burning, as in a continuous spiral, gets its extra wait as a pause
// between the two weld moves). Time 0 is the torch at the plan's first point. Throws InputError for negative or non-finite
// settings.
Timeline BuildTimeline(const Plan& plan, const std::vector<CellSample>& motion, const AxisLimits& limits,
                       const TimelineSettings& settings);

}  // namespace waam::planner
