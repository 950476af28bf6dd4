// Tests of the build's timeline (planner/timeline/timeline.h): sums, trapezoidal moves, arc starts and ends, waits.
#include "planner/timeline/timeline.h"

#include <cmath>

#include <gtest/gtest.h>

#include "models/core/error.h"

namespace waam::planner {
namespace {

PathPoint Pt(double x, double y, double z, bool weld, double speed_mm_s = 10.0) {
  PathPoint p;
  p.p_P = Eigen::Vector3d(x, y, z);
  p.weld = weld;
  p.speed_mm_s = speed_mm_s;
  return p;
}

// `layers` layers of `passes` straight 30 mm passes each, 10 mm apart, at 10 mm/s.
Plan Passes(int layers, int passes) {
  Plan plan;
  for (int l = 0; l < layers; ++l) {
    LayerPath layer;
    layer.index = l;
    const double z = 2.0 * (l + 1);
    for (int k = 0; k < passes; ++k) {
      layer.points.push_back(Pt(0.0, 10.0 * k, z, false));
      layer.points.push_back(Pt(30.0, 10.0 * k, z, true));
    }
    plan.layers.push_back(layer);
  }
  return plan;
}

int Count(const Timeline& t, SpanKind kind) {
  int n = 0;
  for (const TimedSpan& s : t.spans) n += s.kind == kind ? 1 : 0;
  return n;
}

void ExpectConsistent(const Timeline& t) {
  EXPECT_NEAR(t.total_s, t.arc_on_s + t.travel_s + t.wait_s, 1e-9) << "total = arc on + travel + wait";
  double end = 0.0;
  for (const TimedSpan& s : t.spans) {
    EXPECT_DOUBLE_EQ(s.start_s, end) << "spans are contiguous";
    EXPECT_GT(s.end_s, s.start_s);
    end = s.end_s;
  }
  EXPECT_DOUBLE_EQ(end, t.total_s);
  double arc = 0.0, travel = 0.0, wait = 0.0;
  for (const LayerTimes& l : t.layers) arc += l.arc_on_s, travel += l.travel_s, wait += l.wait_s;
  EXPECT_NEAR(arc, t.arc_on_s, 1e-9);
  EXPECT_NEAR(travel, t.travel_s, 1e-9);
  EXPECT_NEAR(wait, t.wait_s, 1e-9);
}

TEST(TrapezoidTimeTest, MatchesTheClosedForms) {
  // Long move: reaches v; t = d/v + v/a. Short move: a triangle; t = 2 sqrt(d/a).
  EXPECT_DOUBLE_EQ(TrapezoidTime(100.0, 50.0, 200.0), 100.0 / 50.0 + 50.0 / 200.0);
  EXPECT_DOUBLE_EQ(TrapezoidTime(4.0, 50.0, 200.0), 2.0 * std::sqrt(4.0 / 200.0));
  // At d = v^2/a both forms give 2 v / a.
  EXPECT_NEAR(TrapezoidTime(12.5, 50.0, 200.0), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(TrapezoidTime(0.0, 50.0, 200.0), 0.0);
  EXPECT_DOUBLE_EQ(TrapezoidTime(10.0, 5.0, std::numeric_limits<double>::infinity()), 2.0);
}

TEST(TimelineTest, SumsArcStartsAndEndsPerPass) {
  const Plan plan = Passes(3, 2);
  TimelineSettings settings;
  settings.arc_start_s = 0.7;
  settings.arc_end_s = 0.4;
  settings.rapid_speed_mm_s = 50.0;
  const Timeline t = BuildTimeline(plan, {}, AxisLimits{}, settings);
  ExpectConsistent(t);
  EXPECT_EQ(Count(t, SpanKind::kArcStart), 6) << "one arc start per pass";
  EXPECT_EQ(Count(t, SpanKind::kArcEnd), 6) << "one arc end per pass";
  EXPECT_EQ(Count(t, SpanKind::kArcOn), 6);
  EXPECT_NEAR(t.arc_on_s, 6 * (30.0 / 10.0 + 0.7 + 0.4), 1e-9);
  // Travel: per layer two moves back to x = 0 (one of them also 10 mm across), plus the 2 mm rise between layers.
  double travel_mm = 0.0;
  const PathPoint* prev = nullptr;
  for (const LayerPath& layer : plan.layers) {
    for (const PathPoint& p : layer.points) {
      if (prev != nullptr && !p.weld) travel_mm += (p.p_P - prev->p_P).norm();
      prev = &p;
    }
  }
  EXPECT_NEAR(t.travel_s, travel_mm / 50.0, 1e-9);
  ASSERT_EQ(t.layers.size(), 3u);
  for (std::size_t l = 0; l < 3; ++l) {
    EXPECT_EQ(t.layers[l].layer, static_cast<int>(l));
    EXPECT_NEAR(t.layers[l].end_s - t.layers[l].start_s,
                2 * (30.0 / 10.0 + 0.7 + 0.4) + std::hypot(30.0, 10.0) / 50.0, 1e-9)
        << "a layer runs from its first arc start to its last arc end";
  }
  EXPECT_DOUBLE_EQ(t.layers[0].start_s, 0.0) << "the first pass starts where the torch stands at time 0";
}

TEST(TimelineTest, DwellsAreWaits) {
  Plan plan = Passes(2, 1);
  plan.layers[0].points[1].dwell_s = 12.5;  // a program's own wait at the end of the first pass
  TimelineSettings settings;
  const Timeline t = BuildTimeline(plan, {}, AxisLimits{}, settings);
  ExpectConsistent(t);
  EXPECT_DOUBLE_EQ(t.wait_s, 12.5);
  EXPECT_DOUBLE_EQ(t.layers[0].wait_s, 12.5);
  // One wait: the torch waits at the point it reached (the pass's arc end follows with the next arc-off move).
  EXPECT_EQ(Count(t, SpanKind::kWait), 1);
}

TEST(TimelineTest, MinLayerTimeWaitsBeforeTheNextLayersFirstArcStart) {
  const Plan plan = Passes(3, 1);
  TimelineSettings settings;
  settings.min_layer_time_s = 60.0;
  settings.extra_wait_before_layer_s = {100.0, 0.0, 7.0};  // layer 0 has no previous layer but still waits
  const Timeline t = BuildTimeline(plan, {}, AxisLimits{}, settings);
  ExpectConsistent(t);
  ASSERT_EQ(t.layers.size(), 3u);
  EXPECT_DOUBLE_EQ(t.layers[0].start_s, 100.0);
  EXPECT_NEAR(t.layers[1].start_s - t.layers[0].start_s, 60.0, 1e-9) << "layer 0 lasts min_layer_time_s";
  EXPECT_NEAR(t.layers[2].start_s - t.layers[1].start_s, 67.0, 1e-9) << "then the extra 7 s before layer 2";
  // The waits (the minimum's, then the extra one) sit right before an arc start.
  for (std::size_t k = 0; k + 1 < t.spans.size(); ++k) {
    if (t.spans[k].kind == SpanKind::kWait) {
      EXPECT_TRUE(t.spans[k + 1].kind == SpanKind::kArcStart || t.spans[k + 1].kind == SpanKind::kWait);
    }
  }
  // A layer already longer than the minimum does not wait.
  settings.min_layer_time_s = 1.0;
  settings.extra_wait_before_layer_s.clear();
  EXPECT_DOUBLE_EQ(BuildTimeline(plan, {}, AxisLimits{}, settings).wait_s, 0.0);
}

TEST(TimelineTest, ExtraWaitPausesAContinuousSpiralBetweenItsLayers) {
  // Two layers welded without an arc end between them (a spiral): layer 1 starts with a weld move.
  Plan plan;
  plan.layers.resize(2);
  plan.layers[0].points = {Pt(0, 0, 2, false), Pt(30, 0, 2, true)};
  plan.layers[1].index = 1;
  plan.layers[1].points = {Pt(30, 0, 4, true), Pt(0, 0, 4, true)};
  TimelineSettings settings;
  const Timeline plain = BuildTimeline(plan, {}, AxisLimits{}, settings);
  ExpectConsistent(plain);
  EXPECT_EQ(Count(plain, SpanKind::kArcStart), 1) << "one pass: the arc burns across the layers";
  settings.extra_wait_before_layer_s = {0.0, 40.0};
  const Timeline t = BuildTimeline(plan, {}, AxisLimits{}, settings);
  ExpectConsistent(t);
  EXPECT_NEAR(t.wait_s, plain.wait_s + 40.0, 1e-9) << "the interpass wait is in the timeline";
  EXPECT_NEAR(t.total_s, plain.total_s + 40.0, 1e-9);
  EXPECT_NEAR(t.layers[1].start_s, plain.layers[1].start_s + 40.0, 1e-9) << "layer 1 starts after the wait";
  EXPECT_EQ(Count(t, SpanKind::kArcStart), 1) << "a pause, not a new pass";
  EXPECT_EQ(Count(t, SpanKind::kArcEnd), 1);
  // min_layer_time_s holds the spiral's layer 0 to 100 s the same way.
  settings.extra_wait_before_layer_s.clear();
  settings.min_layer_time_s = 100.0;
  const Timeline held = BuildTimeline(plan, {}, AxisLimits{}, settings);
  ExpectConsistent(held);
  EXPECT_NEAR(held.layers[1].start_s - held.layers[0].start_s, 100.0, 1e-9) << "layer 0 lasts min_layer_time_s";
  EXPECT_EQ(Count(held, SpanKind::kArcStart), 1) << "a pause, not a new pass";
}

// A two-point plan (a travel move) and a hand-made motion of `n` samples along it, axis `axis` turning by `angle`.
void TravelWithMotion(double length_mm, int axis, double angle_rad, Plan* plan, std::vector<CellSample>* motion) {
  plan->layers.assign(1, LayerPath{});
  plan->layers[0].points = {Pt(0, 0, 0, false), Pt(length_mm, 0, 0, false)};
  motion->clear();
  CellSample s;
  s.point = 0;
  motion->push_back(s);
  const int n = 10;
  for (int k = 1; k <= n; ++k) {
    s.point = 1;
    s.q = Joints8::Zero();
    s.q[axis] = angle_rad * k / n;
    motion->push_back(s);
  }
}

TEST(TimelineTest, TravelIsATrapezoidOnTheLimitingAxis) {
  AxisLimits limits;
  limits.max_speed = Joints8::Constant(2.0);
  limits.max_accel = Joints8::Constant(8.0);
  TimelineSettings settings;
  settings.rapid_speed_mm_s = 1000.0;  // the TCP speed does not bind
  Plan plan;
  std::vector<CellSample> motion;
  // j1 turns 1.5 rad: long move (1.5 >= v^2/a = 0.5): t = d/v + v/a.
  TravelWithMotion(100.0, 0, 1.5, &plan, &motion);
  Timeline t = BuildTimeline(plan, motion, limits, settings);
  ExpectConsistent(t);
  EXPECT_NEAR(t.travel_s, 1.5 / 2.0 + 2.0 / 8.0, 1e-9);
  EXPECT_EQ(Count(t, SpanKind::kTravel), 1);
  // Short move: 0.2 rad < 0.5: t = 2 sqrt(d/a).
  TravelWithMotion(100.0, 0, 0.2, &plan, &motion);
  t = BuildTimeline(plan, motion, limits, settings);
  EXPECT_NEAR(t.travel_s, 2.0 * std::sqrt(0.2 / 8.0), 1e-9);
  // The TCP binds when its speed is the lower limit: 100 mm at 10 mm/s, the acceleration from j1 (0.2 rad over
  // the move: u'' <= 8 / 0.2 = 40 /s^2, u' <= 0.1 /s): t = 1/0.1 + 0.1/40.
  settings.rapid_speed_mm_s = 10.0;
  t = BuildTimeline(plan, motion, limits, settings);
  EXPECT_NEAR(t.travel_s, 10.0 + 0.1 / 40.0, 1e-9);
  // The positioner turning with the torch standing still on the part: a positioner span.
  settings.rapid_speed_mm_s = 1000.0;
  TravelWithMotion(0.0, 7, 1.5, &plan, &motion);
  t = BuildTimeline(plan, motion, limits, settings);
  EXPECT_EQ(Count(t, SpanKind::kPositioner), 1);
  EXPECT_NEAR(t.travel_s, 1.5 / 2.0 + 2.0 / 8.0, 1e-9);
}

TEST(TimelineTest, RefusesNegativeSettings) {
  const Plan plan = Passes(1, 1);
  TimelineSettings settings;
  settings.arc_start_s = -1.0;
  try {
    BuildTimeline(plan, {}, AxisLimits{}, settings);
    FAIL() << "a negative arc start time must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("arc_start_s"), std::string::npos) << e.what();
  }
  settings.arc_start_s = 0.0;
  settings.extra_wait_before_layer_s = {-2.0};
  EXPECT_THROW(BuildTimeline(plan, {}, AxisLimits{}, settings), InputError);
}

}  // namespace
}  // namespace waam::planner
