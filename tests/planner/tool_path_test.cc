// Tests of the path statistics (planner/path/tool_path.h).
#include "planner/path/tool_path.h"
#include "planner/timeline/timeline.h"

#include <cmath>

#include <gtest/gtest.h>

namespace waam::planner {
namespace {

PathPoint At(double x, double y, double z, bool weld) {
  PathPoint p;
  p.p_P = Eigen::Vector3d(x, y, z);
  p.speed_mm_s = 10.0;
  p.weld = weld;
  return p;
}

TEST(ComputeStatsTest, TravelIntoALayerCountsAsTravel) {
  // Two layers of one 30 mm pass each; the second starts 40 mm (x) and 2 mm (z) away from where the first ended.
  Plan plan;
  plan.layers.resize(2);
  plan.layers[0].points = {At(0, 0, 2, false), At(30, 0, 2, true)};
  plan.layers[1].index = 1;
  plan.layers[1].points = {At(-10, 0, 4, false), At(20, 0, 4, true)};
  const PathStats s = ComputeStats(plan);
  EXPECT_EQ(s.passes, 2u);
  EXPECT_DOUBLE_EQ(s.weld_length_mm, 60.0);
  const double hop = std::hypot(40.0, 2.0);
  EXPECT_DOUBLE_EQ(s.travel_length_mm, hop) << "the move from layer 0's last point to layer 1's first point";
  TimelineSettings timing;
  timing.arc_start_s = timing.arc_end_s = 0.0;
  timing.rapid_speed_mm_s = 100.0;
  EXPECT_DOUBLE_EQ(BuildTimeline(plan, {}, AxisLimits{}, timing).total_s, 60.0 / 10.0 + hop / 100.0)
      << "weld at 10 mm/s, travel at the rapid 100 mm/s";
}

TEST(ComputeStatsTest, ALayerContinuingTheSpiralIsOnePass) {
  Plan plan;
  plan.layers.resize(2);
  plan.layers[0].points = {At(0, 0, 2, false), At(30, 0, 2, true)};
  plan.layers[1].points = {At(30, 10, 4, true), At(0, 10, 4, true)};
  const PathStats s = ComputeStats(plan);
  EXPECT_EQ(s.passes, 1u);
  EXPECT_DOUBLE_EQ(s.travel_length_mm, 0.0);
  EXPECT_NEAR(s.weld_length_mm, 30.0 + std::hypot(10.0, 2.0) + 30.0, 1e-12);
}

}  // namespace
}  // namespace waam::planner
