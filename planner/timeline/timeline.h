// The build's timeline: every second of a plan from the first arc start to the last arc end, split into arc on,
// arc start/end, travel, positioner moves and waits (issue "Time and heat", part 1).
#pragma once

#include <cstddef>
#include <vector>

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

}  // namespace waam::planner
