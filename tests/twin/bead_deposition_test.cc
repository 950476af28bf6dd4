// Tests of the deposition twin: volume balance, bead shape, blending, start/stop and settings validation.
#include "twin/deposition/bead_deposition.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "tests/twin/test_paths.h"

namespace waam::twin {
namespace {

using ::testing::HasSubstr;
using testing::AddPass;

planner::SimulationSettings Settings(double voxel) {
  planner::SimulationSettings s;
  s.voxel_mm = voxel;
  return s;
}

TEST(BeadDeposition, StraightBeadConservesVolume) {
  planner::Plan plan;
  planner::LayerPath layer;
  AddPass(&layer, {{0, 0}, {80, 0}}, 2.0, 6.0, 2.0, 8.0);
  plan.layers.push_back(layer);
  const Depositor d = DepositPlan(plan, Settings(0.5), 100.0, nullptr);
  ASSERT_EQ(d.beads().size(), 1u);
  EXPECT_NEAR(d.grid().OccupiedVolume(), d.expected_volume_mm3(), 0.02 * d.expected_volume_mm3())
      << "deposited volume must equal the bead area x length";
  // Away from the start and stop, the bead is 2wh/3 per mm: 8 mm^2.
  EXPECT_NEAR(d.expected_volume_mm3() / 80.0, 8.0, 0.8);
}

TEST(BeadDeposition, FlatBeadHasParabolicWidthAndHeight) {
  planner::Plan plan;
  planner::LayerPath layer;
  AddPass(&layer, {{0, 0}, {60, 0}}, 2.0, 6.0, 2.0, 8.0);
  plan.layers.push_back(layer);
  planner::SimulationSettings s = Settings(0.25);
  const Depositor d = DepositPlan(plan, s, 100.0, nullptr);
  // Cross-section at x = 30: count the column heights.
  double area = 0.0, max_h = 0.0, min_y = 1e9, max_y = -1e9;
  const double v = d.grid().voxel_mm();
  for (int j = -20; j <= 20; ++j) {
    int n = 0;
    for (int k = 0; k < 40; ++k) n += d.grid().Occupied(VoxelIndex(120, j, k)) ? 1 : 0;
    if (n == 0) continue;
    area += n * v * v;
    max_h = std::max(max_h, n * v);
    min_y = std::min(min_y, j * v);
    max_y = std::max(max_y, (j + 1) * v);
  }
  EXPECT_NEAR(area, 8.0, 0.8) << "section area 2wh/3 (eq. 3.3)";
  EXPECT_NEAR(max_h, 2.0, 0.3) << "crown at the planned bead height";
  EXPECT_NEAR(max_y - min_y, 6.0, 1.0) << "footprint as wide as the bead";
}

TEST(BeadDeposition, InvalidSettingsAreRefused) {
  planner::SimulationSettings s = Settings(0.05);
  try {
    Depositor d(s);
    FAIL() << "expected InputError for voxel_mm = 0.05";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("simulation.voxel_mm"));
  }
  s = Settings(0.5);
  s.blend = "round";
  EXPECT_THROW(Depositor{s}, InputError);
}

TEST(BeadDeposition, VoxelLimitGivesClearError) {
  planner::Plan plan;
  planner::LayerPath layer;
  AddPass(&layer, {{0, 0}, {50, 0}}, 2.0, 6.0, 2.0, 8.0);
  plan.layers.push_back(layer);
  planner::SimulationSettings s = Settings(0.5);
  s.max_voxels = 1000;
  try {
    DepositPlan(plan, s, 100.0, nullptr);
    FAIL() << "expected InputError past max_voxels";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("max_voxels = 1000"));
  }
}

TEST(BeadDeposition, WeldMoveWithoutSpeedIsRefused) {
  planner::Plan plan;
  planner::LayerPath layer;
  AddPass(&layer, {{0, 0}, {50, 0}}, 2.0, 6.0, 2.0, 0.0);
  plan.layers.push_back(layer);
  try {
    DepositPlan(plan, Settings(0.5), 100.0, nullptr);
    FAIL() << "expected InputError for speed 0";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("layer 0 point 1"));
  }
}

TEST(ExecutedPath, CornerIsBlendedAndShorter) {
  std::vector<ExecutedPoint> raw(3);
  raw[0].p_P = {0, 0, 0};
  raw[1].p_P = {20, 0, 0};
  raw[2].p_P = {20, 20, 0};
  for (auto& p : raw) p.speed_mm_s = 10.0, p.bead_width_mm = 6, p.bead_height_mm = 2;
  planner::SimulationSettings s = Settings(0.5);
  s.blend = "fixed";
  s.blend_radius_mm = 4.0;
  const ExecutedPass pass = BlendPass(raw, s, 0.5);
  // The arc of radius 4 replaces 2 x 4 mm of the corner by a quarter circle (2 pi / 4 x 4 = 6.28 mm).
  EXPECT_NEAR(pass.length_mm(), 40.0 - 8.0 + 2.0 * M_PI, 0.05);
  double closest = 1e9;
  for (const auto& p : pass.points) closest = std::min(closest, (p.p_P - raw[1].p_P).norm());
  EXPECT_NEAR(closest, 4.0 * (std::sqrt(2.0) - 1.0), 0.05) << "the TCP must not reach the vertex";
  s.blend = "none";
  EXPECT_NEAR(BlendPass(raw, s, 0.5).length_mm(), 40.0, 1e-9);
}

TEST(ExecutedPath, StartIsTallerAndStopShrinks) {
  ExecutedPass pass;
  pass.points.resize(2);
  pass.points[1].p_P = {100, 0, 0};
  pass.points[1].s_mm = 100;
  pass.points[1].bead_width_mm = 6;
  pass.points[1].bead_height_mm = 2;
  const planner::SimulationSettings s = Settings(0.5);
  EXPECT_NEAR(SectionAt(pass, 1, 0.0, s).height_mm, 2.0 * s.start_height_factor, 1e-9);
  EXPECT_NEAR(SectionAt(pass, 1, 50.0, s).height_mm, 2.0, 1e-9);
  EXPECT_NEAR(SectionAt(pass, 1, 100.0, s).height_mm, 2.0 * s.stop_height_factor, 1e-9);
}

}  // namespace
}  // namespace waam::twin
