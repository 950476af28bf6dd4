// The thermal run along a timeline: interpass waits hold their limit and appear in the rebuilt timeline, the energy
// balance closes, probe histories are sampled evenly, and a probe outside the metal is refused.
#include "analysis/thermal_run.h"

#include <cmath>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/scenario.h"
#include "models/core/error.h"
#include "planner/plan_scenario.h"

namespace waam::analysis {
namespace {

// A timeline of the plan without a cell, for driving the thermal run in these tests: weld moves take their length
// over their speed, each pass 0.5 s of arc start and 0.3 s of arc end, arc-off moves their length at 100 mm/s, and
// `extra[l]` s of wait before layer l's first arc start.
planner::Timeline StraightTimeline(const planner::Plan& plan, const std::vector<double>& extra) {
  planner::Timeline t;
  double now = 0.0;
  auto add = [&](planner::SpanKind kind, double seconds, int layer, std::size_t point) {
    if (seconds <= 0.0) return;
    t.spans.push_back({kind, now, now + seconds, layer, point});
    planner::LayerTimes& l = t.layers[layer];
    (kind == planner::SpanKind::kWait ? l.wait_s
     : kind == planner::SpanKind::kTravel ? l.travel_s
                                           : l.arc_on_s) += seconds;
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
      if (!p.weld) {
        add(planner::SpanKind::kTravel, length / 100.0, l, i);
        continue;
      }
      if (!layer.points[i - 1].weld || i == 1) {
        if (first && li < extra.size()) add(planner::SpanKind::kWait, extra[li], l, i - 1);
        if (first) t.layers[li].start_s = now;
        first = false;
        add(planner::SpanKind::kArcStart, 0.5, l, i - 1);
      }
      add(planner::SpanKind::kArcOn, length / p.speed_mm_s, l, i);
      if (i + 1 == layer.points.size() || !layer.points[i + 1].weld) {
        add(planner::SpanKind::kArcEnd, 0.3, l, i);
        t.layers[li].end_s = now;
      }
    }
  }
  for (const planner::LayerTimes& l : t.layers) {
    t.arc_on_s += l.arc_on_s;
    t.travel_s += l.travel_s;
    t.wait_s += l.wait_s;
  }
  t.total_s = now;
  return t;
}

struct Planned {
  Scenario scenario;
  planner::Plan plan;
};

Planned PlannedWall(const std::vector<std::string>& overrides = {}) {
  Planned p{LoadScenario(std::string(WAAM_SOURCE_DIR) + "/scenarios/thermal/wall_interpass.yaml", overrides), {}};
  p.plan = planner::PlanScenario(p.scenario, nullptr).plan;
  return p;
}

ThermalRunResult RunAlongStraightTimeline(const Planned& p) {
  return RunThermalModel(p.scenario, p.plan,
                         [&](const std::vector<double>& extra) { return StraightTimeline(p.plan, extra); }, nullptr);
}

// The scenario's build, run once for the tests that read it.
const Planned& InterpassWall() {
  static const Planned wall = PlannedWall();
  return wall;
}
const ThermalRunResult& InterpassRun() {
  static const ThermalRunResult r = RunAlongStraightTimeline(InterpassWall());
  return r;
}

TEST(ThermalRun, InterpassWaitsHoldTheLimitAndAreInTheTimeline) {
  const Planned& wall = InterpassWall();
  const double max_c = wall.scenario.process.interpass.max_c;
  const ThermalRunResult& r = InterpassRun();
  ASSERT_EQ(r.layers.size(), wall.plan.layers.size());
  double waits = 0.0;
  for (const ThermalLayer& l : r.layers) {
    SCOPED_TRACE(l.layer);
    waits += l.wait_s;
    EXPECT_TRUE(std::isfinite(l.peak_c));
    EXPECT_GT(l.peak_c, max_c) << "the arc heats the metal past the interpass limit";
    if (l.layer == 0) continue;
    EXPECT_TRUE(l.interpass_reached);
    EXPECT_LE(l.interpass_c, max_c) << "the layer started above the interpass limit";
    // The rebuilt timeline puts each wait where the run waited: the layer starts at the same time in both.
    EXPECT_NEAR(r.timeline.layers[l.layer].start_s, l.start_s, 1e-6);
  }
  EXPECT_GT(waits, 0.0) << "a 200 degC limit on this wall must make the build wait";
  EXPECT_NEAR(r.timeline.wait_s, waits, 1e-9) << "the timeline's waits are the interpass waits";
  EXPECT_NEAR(r.sample_time_s.back(), r.timeline.total_s, 1e-6) << "the run ends at the timeline's end";
}

TEST(ThermalRun, WithoutTheLimitTheLayersStartHotter) {
  // The same build with no interpass limit: no waits, and some layer starts above 200 degC (so the test above can
  // fail when the waits do not work).
  const Planned wall = PlannedWall({"process.interpass.max_c=2900"});
  const ThermalRunResult r = RunAlongStraightTimeline(wall);
  double hottest_start = 0.0;
  for (const ThermalLayer& l : r.layers) {
    EXPECT_EQ(l.wait_s, 0.0);
    if (l.layer > 0) hottest_start = std::max(hottest_start, l.interpass_c);
  }
  EXPECT_GT(hottest_start, 200.0);
}

TEST(ThermalRun, EnergyBalanceClosesAndProbesAreSampledEvenly) {
  const Planned& wall = InterpassWall();
  const ThermalRunResult& r = InterpassRun();
  EXPECT_NEAR(r.energy.input_j, wall.scenario.process.arc.efficiency * r.arc_energy_j, 1e-6 * r.energy.input_j)
      << "heat in = efficiency x arc energy";
  EXPECT_LT(r.energy.RelativeError(), 0.01) << "input " << r.energy.input_j << " J, stored " << r.energy.stored_j
                                            << " J, lost " << r.energy.lost_j << " J";
  const double dt = wall.scenario.thermal.sample_s;
  for (std::size_t i = 1; i + 1 < r.sample_time_s.size(); ++i) {
    ASSERT_NEAR(r.sample_time_s[i] - r.sample_time_s[i - 1], dt, 1e-6) << "sample " << i;
  }
  ASSERT_EQ(r.probes.size(), 2u);
  const ThermalProbeHistory& plate = r.probes[0];
  const ThermalProbeHistory& wall_probe = r.probes[1];
  EXPECT_TRUE(std::isfinite(plate.temperature_c.front())) << "the plate probe is in metal from the start";
  EXPECT_TRUE(std::isnan(wall_probe.temperature_c.front())) << "the wall probe has no metal before its layer";
  EXPECT_TRUE(std::isfinite(wall_probe.temperature_c.back()));
  double max_c = -1e9;
  for (double t : wall_probe.temperature_c) {
    if (std::isfinite(t)) max_c = std::max(max_c, t);
  }
  EXPECT_EQ(wall_probe.max_c, max_c);
  EXPECT_GT(wall_probe.max_c, plate.max_c) << "the wall is hotter than the plate beside it";
  EXPECT_EQ(r.fields.size(), wall.plan.layers.size());
}

TEST(ThermalRun, ProbeOutsideThePlateAndThePartIsRefused) {
  const Planned wall = PlannedWall({"thermal.probes.air=[0, 0, 50]"});
  try {
    ThermalSettingsFor(wall.scenario, wall.plan);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("thermal.probes.air = [0, 0, 50]: outside the plate"));
  }
}

}  // namespace
}  // namespace waam::analysis
