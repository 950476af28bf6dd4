// A continuous spiral (a layer whose first move is a weld move) runs as one pass across layers in the twin.
#include <gtest/gtest.h>

#include "twin/deposition/executed_path.h"

namespace waam::twin {
namespace {

// Two square loops 1.5 mm apart; the second layer's first point continues the first layer's pass when `spiral`.
planner::Plan TwoLoops(bool spiral) {
  planner::Plan plan;
  const double corners[5][2] = {{0, 0}, {20, 0}, {20, 20}, {0, 20}, {0, 0}};
  for (int l = 0; l < 2; ++l) {
    planner::LayerPath layer;
    layer.index = l;
    for (int k = 0; k < 5; ++k) {
      planner::PathPoint p;
      p.p_P = Eigen::Vector3d(corners[k][0], corners[k][1], 1.5 * (l + 1));
      p.bead_width_mm = 4.0;
      p.bead_height_mm = 1.5;
      p.speed_mm_s = 5.0;
      p.weld = k > 0 || (l == 1 && spiral);
      layer.points.push_back(p);
    }
    plan.layers.push_back(layer);
  }
  return plan;
}

TEST(SpiralPass, ContinuesAcrossLayers) {
  planner::SimulationSettings settings;
  settings.blend = "none";
  const std::vector<ExecutedPass> spiral = ExecutePlan(TwoLoops(true), settings, 100.0);
  ASSERT_EQ(spiral.size(), 1u) << "a weld move into the next layer continues the pass";
  EXPECT_EQ(spiral[0].layer, 0) << "the pass keeps the layer it started in";
  EXPECT_NEAR(spiral[0].length_mm(), 80.0 + 1.5 + 80.0, 1e-9) << "both loops and the climb between them";
  const std::vector<ExecutedPass> layers = ExecutePlan(TwoLoops(false), settings, 100.0);
  ASSERT_EQ(layers.size(), 2u) << "an arc-off first point starts a new pass";
  EXPECT_EQ(layers[1].layer, 1);
}

}  // namespace
}  // namespace waam::twin
