// Tests of the deposition twin: volume balance, bead shape, blending, start/stop and settings validation.
#include "tests/twin/twin_settings.h"
#include "models/core/numbers.h"
#include "twin/deposition/bead_deposition.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "tests/twin/test_paths.h"

namespace waam::twin {
namespace {

using ::testing::HasSubstr;
using testing::AddPass;

twin::SimulationSettings Settings(double voxel) {
  twin::SimulationSettings s = twin::TestSimulationSettings();
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
  twin::SimulationSettings s = Settings(0.25);
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
  twin::SimulationSettings s = Settings(0.05);
  try {
    Depositor d(s);
    FAIL() << "expected InputError for voxel_mm = 0.05";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("simulation.voxel_mm"));
  }
}

TEST(BeadDeposition, VoxelLimitGivesClearError) {
  planner::Plan plan;
  planner::LayerPath layer;
  AddPass(&layer, {{0, 0}, {50, 0}}, 2.0, 6.0, 2.0, 8.0);
  plan.layers.push_back(layer);
  twin::SimulationSettings s = Settings(0.5);
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

// Multi-axis: a bead laid with the torch horizontal (tool along +x) against the +x side of a block grows along +x,
// its section swept in the torch frame; the volume still balances.
TEST(BeadDeposition, HorizontalTorchBuildsSideways) {
  twin::SimulationSettings s = Settings(0.5);
  Depositor d(s);
  // A block 0 <= x < 10, 0 <= y < 40, 0 <= z < 20 deposited as vertical beads first.
  planner::Plan block;
  for (int k = 0; k < 10; ++k) {
    planner::LayerPath layer;
    layer.index = k;
    for (double x : {1.5, 5.0, 8.5}) AddPass(&layer, {{x, 0}, {x, 40}}, 2.0 * (k + 1), 4.0, 2.0, 8.0);
    block.layers.push_back(layer);
  }
  for (const ExecutedPass& pass : ExecutePlan(block, s, 100.0)) d.DepositPass(pass);
  int face = 0;  // the block's largest x at mid height
  for (int i = 0; i < 60; ++i) face = d.grid().Occupied(VoxelIndex(i, 40, 20)) ? i : face;
  const double before = d.grid().OccupiedVolume();
  const double expected_before = d.expected_volume_mm3();
  // The side bead: along y at mid height, TCP just outside the face, torch pointing along +x.
  ExecutedPass side;
  side.layer = 10;
  for (int n = 0; n < 2; ++n) {
    ExecutedPoint p;
    p.p_P = Eigen::Vector3d((face + 1) * 0.5 + 2.0, 5.0 + 30.0 * n, 10.0);
    p.tool_dir_P = Eigen::Vector3d::UnitX();
    p.bead_width_mm = 4.0;
    p.bead_height_mm = 2.0;
    p.speed_mm_s = 8.0;
    p.s_mm = 30.0 * n;
    side.points.push_back(p);
  }
  const std::uint32_t bead = d.DepositPass(side);
  const double added = d.grid().OccupiedVolume() - before;
  const double expected = d.expected_volume_mm3() - expected_before;
  EXPECT_NEAR(added, expected, 0.02 * expected) << "the sideways bead must conserve its volume";
  // At the middle of the bead (y = 20, z = 10) the new metal sits beyond the old face, about h thick along +x.
  int grown = 0;
  for (int i = face + 1; i < face + 20; ++i) grown += d.grid().Occupied(VoxelIndex(i, 40, 20)) ? 1 : 0;
  EXPECT_NEAR(grown * 0.5, 2.0, 0.75) << "crown height measured along the torch axis";
  // The side bead lies beside the face, within the (spread) bead width around z = 10.
  double x_min = 1e9, z_lo = 1e9, z_hi = -1e9;
  d.grid().ForEach([&](const VoxelIndex& v, const VoxelData& data) {
    if (data.bead != bead) return;
    const Eigen::Vector3d c = d.grid().Center(v);
    // Away from the block beads' start/stop craters, whose pits the molten side bead fills.
    if (c.y() > 10.0 && c.y() < 30.0) x_min = std::min(x_min, c.x());
    z_lo = std::min(z_lo, c.z());
    z_hi = std::max(z_hi, c.z());
  });
  EXPECT_GT(x_min, (face - 2) * 0.5) << "the bead must not reach back into the block";
  EXPECT_GT(z_lo, 10.0 - 0.5 * 4.0 * 1.3 - 0.5);
  EXPECT_LT(z_hi, 10.0 + 0.5 * 4.0 * 1.3 + 0.5);
}

// A bead laid on the edge of a wall, half of it over air: the hanging half runs down the side at most
// edge_sag_factor x h below the supported ground and never fills the air down to the substrate.
TEST(BeadDeposition, BeadOverAFreeEdgeDoesNotFillTheAirBelow) {
  twin::SimulationSettings s = Settings(0.5);
  Depositor d(s);
  planner::Plan wall;
  for (int k = 0; k < 16; ++k) {
    planner::LayerPath layer;
    layer.index = k;
    for (double x : {2.0, 5.0, 8.0}) AddPass(&layer, {{x, 0}, {x, 40}}, 2.0 * (k + 1), 4.0, 2.0, 8.0);
    wall.layers.push_back(layer);
  }
  for (const ExecutedPass& pass : ExecutePlan(wall, s, 100.0)) d.DepositPass(pass);
  double top = 0.0;  // wall height at its middle
  for (int k = 0; k < 120; ++k) top = d.grid().Occupied(VoxelIndex(10, 40, k)) ? (k + 1) * 0.5 : top;
  const double before = d.grid().OccupiedVolume();
  const double expected_before = d.expected_volume_mm3();
  planner::Plan edge;
  planner::LayerPath layer;
  layer.index = 16;
  const double x_edge = 10.0;  // the outer toe of the x = 8 beads
  AddPass(&layer, {{x_edge, 5}, {x_edge, 35}}, top + 2.0, 4.0, 2.0, 8.0);
  edge.layers.push_back(layer);
  std::uint32_t bead = 0;
  for (const ExecutedPass& pass : ExecutePlan(edge, s, 100.0)) bead = d.DepositPass(pass);
  EXPECT_NEAR(d.grid().OccupiedVolume() - before, d.expected_volume_mm3() - expected_before,
              0.02 * (d.expected_volume_mm3() - expected_before));
  double lowest = 1e9;
  d.grid().ForEach([&](const VoxelIndex& v, const VoxelData& data) {
    if (data.bead == bead) lowest = std::min(lowest, d.grid().Center(v).z());
  });
  std::printf("free edge: wall top %.2f mm, lowest voxel of the edge bead %.2f mm\n", top, lowest);
  // It may run down the wall's own rounded flank within the ground search (4 h + 2 mm under the crown) and sag
  // edge_sag_factor x h below that, but no further: half-way down a 25 mm wall it has stopped.
  EXPECT_GT(lowest, top - 4.0 * 2.0 - 2.0 - s.edge_sag_factor * 2.0 - 1.0)
      << "the hanging metal must stay near the top of the wall (top " << top << " mm)";
  EXPECT_GT(lowest, 0.5 * top) << "the hanging metal must not fill the air down the side of the wall";
}

TEST(ExecutedPath, CornerIsBlendedAndShorter) {
  std::vector<ExecutedPoint> raw(3);
  raw[0].p_P = {0, 0, 0};
  raw[1].p_P = {20, 0, 0};
  raw[2].p_P = {20, 20, 0};
  for (auto& p : raw) p.speed_mm_s = 10.0, p.bead_width_mm = 6, p.bead_height_mm = 2;
  twin::SimulationSettings s = Settings(0.5);
  s.blend = twin::Blend::kFixed;
  s.blend_radius_mm = 4.0;
  const ExecutedPass pass = BlendPass(raw, s, 0.5);
  // The arc of radius 4 replaces 2 x 4 mm of the corner by a quarter circle (2 pi / 4 x 4 = 6.28 mm).
  EXPECT_NEAR(pass.length_mm(), 40.0 - 8.0 + 2.0 * kPi, 0.05);
  double closest = 1e9;
  for (const auto& p : pass.points) closest = std::min(closest, (p.p_P - raw[1].p_P).norm());
  EXPECT_NEAR(closest, 4.0 * (std::sqrt(2.0) - 1.0), 0.05) << "the TCP must not reach the vertex";
  s.blend = twin::Blend::kNone;
  EXPECT_NEAR(BlendPass(raw, s, 0.5).length_mm(), 40.0, 1e-9);
}

TEST(ExecutedPath, StartIsTallerAndStopShrinks) {
  ExecutedPass pass;
  pass.points.resize(2);
  pass.points[1].p_P = {100, 0, 0};
  pass.points[1].s_mm = 100;
  pass.points[1].bead_width_mm = 6;
  pass.points[1].bead_height_mm = 2;
  const twin::SimulationSettings s = Settings(0.5);
  EXPECT_NEAR(SectionAt(pass, 1, 0.0, s).height_mm, 2.0 * s.start_height_factor, 1e-9);
  EXPECT_NEAR(SectionAt(pass, 1, 50.0, s).height_mm, 2.0, 1e-9);
  EXPECT_NEAR(SectionAt(pass, 1, 100.0, s).height_mm, 2.0 * s.stop_height_factor, 1e-9);
}

}  // namespace
}  // namespace waam::twin
