// A continuous spiral (a layer whose first move is a weld move) runs as one pass across layers in the twin.
#include <gtest/gtest.h>

#include "tests/twin/twin_settings.h"
#include "twin/deposition/bead_deposition.h"
#include "twin/deposition/executed_path.h"

namespace waam::twin {
namespace {

// Two square loops 1.5 mm apart; the second layer's first point continues the first layer's pass when `spiral`.
planner::Plan TwoLoops(bool spiral, double second_speed_mm_s = 5.0) {
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
      p.speed_mm_s = l == 0 ? 5.0 : second_speed_mm_s;
      p.weld = k > 0 || (l == 1 && spiral);
      layer.points.push_back(p);
    }
    plan.layers.push_back(layer);
  }
  return plan;
}

TEST(SpiralPass, ContinuesAcrossLayers) {
  twin::SimulationSettings settings = twin::TestSimulationSettings();
  settings.blend = twin::Blend::kNone;
  const std::vector<ExecutedPass> spiral = ExecutePlan(TwoLoops(true), settings, 100.0);
  ASSERT_EQ(spiral.size(), 1u) << "a weld move into the next layer continues the pass";
  EXPECT_EQ(spiral[0].layer, 0) << "the pass keeps the layer it started in";
  EXPECT_NEAR(spiral[0].length_mm(), 80.0 + 1.5 + 80.0, 1e-9) << "both loops and the climb between them";
  const std::vector<ExecutedPass> layers = ExecutePlan(TwoLoops(false), settings, 100.0);
  ASSERT_EQ(layers.size(), 2u) << "an arc-off first point starts a new pass";
  EXPECT_EQ(layers[1].layer, 1);
  // The first loop at 5 mm/s, then the arc-off move up into the second layer at the rapid speed.
  EXPECT_NEAR(layers[1].start_time_s, 80.0 / 5.0 + 1.5 / 100.0, 1e-9) << "the move into a layer is timed";
}

TEST(SpiralPass, VoxelsKnowTheirLayerAndTime) {
  // One pass through two layers, the second at twice the speed: 80 mm at 5 mm/s (16 s), then 81.5 mm at 10 mm/s
  // (8.15 s). Voxels are stamped with the time the torch laid them (the sum of length / speed along the pass) and
  // belong to the layer of the move that laid them, not to the pass's first layer.
  twin::SimulationSettings settings = twin::TestSimulationSettings();
  settings.blend = twin::Blend::kNone;
  settings.voxel_mm = 0.5;
  const std::vector<ExecutedPass> passes = ExecutePlan(TwoLoops(true, 10.0), settings, 100.0);
  ASSERT_EQ(passes.size(), 1u);
  Depositor depositor(settings);
  depositor.DepositPass(passes[0]);
  const VoxelGrid& grid = depositor.grid();
  double latest = 0.0;
  int upper_in_layer_1 = 0, upper = 0, lower_in_layer_0 = 0, lower = 0;
  grid.ForEach([&](const VoxelIndex& v, const VoxelData& d) {
    latest = std::max(latest, static_cast<double>(d.time_s));
    const Eigen::Vector3d c = grid.Center(v);
    // Under the middle of the first side, y = 0 (the second bead also fills the first one's flanks down to the
    // plate, and the outside of the corners; the climb is at the corner (0, 0)).
    if (c.x() < 8.0 || c.x() > 17.0 || std::abs(c.y()) > 1.0) return;
    const double z = c.z();
    if (z > 2.0) ++upper, upper_in_layer_1 += depositor.LayerOf(d) == 1;
    if (z < 1.0) ++lower, lower_in_layer_0 += depositor.LayerOf(d) == 0;
  });
  EXPECT_NEAR(latest, 16.0 + 8.15, 0.05) << "the last metal at the end of the pass (a stamp of s / v would be 16.15 s)";
  ASSERT_GT(upper, 20);
  ASSERT_GT(lower, 20);
  EXPECT_EQ(upper_in_layer_1, upper) << "metal above the first loop was laid in layer 1";
  EXPECT_EQ(lower_in_layer_0, lower);
}

}  // namespace
}  // namespace waam::twin
