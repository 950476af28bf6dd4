// Arc start and stop in the deposition twin: the crater's metal in its lip, a crater beside a later bead, a cold start.
#include <cmath>

#include <gtest/gtest.h>

#include "tests/twin/twin_settings.h"
#include "tests/twin/test_paths.h"
#include "twin/deposition/bead_deposition.h"

namespace waam::twin {
namespace {

using testing::AddPass;

constexpr double kW = 6.0;      // bead width, mm
constexpr double kH = 2.0;      // bead height, mm (area 2wh/3 = 8 mm^2)
constexpr double kVoxel = 0.25; // mm

twin::SimulationSettings Settings(const std::string& stop_crater, const std::string& start_wetting) {
  twin::SimulationSettings s = twin::TestSimulationSettings();
  s.voxel_mm = kVoxel;
  s.stop_crater = ParseEnum<twin::StopCrater>(stop_crater).value();
  s.start_wetting = ParseEnum<twin::StartWetting>(start_wetting).value();
  return s;
}

// Top of the metal in the voxel column over (x, y), mm (0 on the bare substrate).
double Top(const Depositor& d, double x, double y) {
  const int i = static_cast<int>(std::floor(x / kVoxel));
  const int j = static_cast<int>(std::floor(y / kVoxel));
  for (int k = 60; k >= 0; --k) {
    if (d.grid().Occupied(VoxelIndex(i, j, k))) return (k + 1) * kVoxel;
  }
  return 0.0;
}

// Mean top over x in [x0, x1] at y, mm.
double MeanTop(const Depositor& d, double x0, double x1, double y) {
  double sum = 0.0;
  int n = 0;
  for (double x = x0; x <= x1; x += kVoxel, ++n) sum += Top(d, x, y);
  return sum / n;
}

ExecutedPass Straight(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double z, int layer) {
  planner::LayerPath path;
  AddPass(&path, {a, b}, z, kW, kH, 10.0);
  planner::Plan plan;
  path.index = layer;
  plan.layers.push_back(path);
  ExecutedPass pass = ExecutePlan(plan, Settings("lip", "cold"), 100.0).front();
  pass.layer = layer;
  return pass;
}

TEST(ArcStop, CraterMetalFreezesInItsLipAndIsNotLost) {
  const ExecutedPass pass = Straight({0, 0}, {80, 0}, kH, 0);
  Depositor lip(Settings("lip", "cold"));
  Depositor lost(Settings("lost", "cold"));
  lip.DepositPass(pass);
  lost.DepositPass(pass);
  const twin::SimulationSettings s = twin::TestSimulationSettings();
  // The crater's mean deficit for the default stop factors: -(a + b)/2 - ab/3 of the section over stop_length_mm.
  const double a = s.stop_height_factor - 1.0, b = s.stop_width_factor - 1.0;
  const double crater_mm3 = (-(a + b) / 2.0 - a * b / 3.0) * 8.0 * s.stop_length_mm;
  EXPECT_NEAR(lip.expected_volume_mm3() - lost.expected_volume_mm3(), crater_mm3, 0.02 * crater_mm3)
      << "the lip must hold exactly the metal the crater lacks";
  EXPECT_NEAR(lip.grid().OccupiedVolume(), lip.expected_volume_mm3(), 0.01 * lip.expected_volume_mm3())
      << "deposited volume must equal what the wire brought";
  // The wire brings 8 mm^2 x 80 mm; only the start's assumed shape (x1.25 high, x0.85 wide) adds a little.
  EXPECT_NEAR(lip.expected_volume_mm3(), 640.0, 0.01 * 640.0);
  const double mid = MeanTop(lip, 30.0, 40.0, 0.0);
  EXPECT_GT(MeanTop(lip, 65.0, 71.0, 0.0), mid + 0.2) << "the pool's tail before the crater stands higher";
  EXPECT_LT(MeanTop(lip, 77.5, 79.5, 0.0), mid - 0.4) << "the crater at the arc stop";
  EXPECT_LT(MeanTop(lost, 65.0, 71.0, 0.0), mid + 0.1) << "without the lip the bead before the crater is level";
}

TEST(ArcStop, ContinuousPassIsUnchangedAwayFromItsEnds) {
  // One long pass on flat ground: the new start and stop change nothing between the start length and the lip.
  const ExecutedPass pass = Straight({0, 0}, {120, 0}, kH, 0);
  Depositor now(Settings("lip", "cold"));
  Depositor before(Settings("lost", "hot"));
  now.DepositPass(pass);
  before.DepositPass(pass);
  int differing = 0, compared = 0;
  for (double x = 0.0; x < 120.0 - 2.0 * 8.0 - 1.0; x += kVoxel) {
    for (double y = -4.0; y <= 4.0; y += kVoxel, ++compared) {
      if (Top(now, x, y) != Top(before, x, y)) ++differing;
    }
  }
  EXPECT_EQ(differing, 0) << "of " << compared << " columns before the lip, all must be as before";
}

TEST(ArcStop, CraterBesideALaterParallelBeadSurvivesBeyondItsFootprint) {
  // Bead A stops at x = 60; bead B, laid later 0.6 w beside it, runs on past A's end. B's pool wets only its own
  // footprint (y > 3.6 - 3 mm and the edge spread): the far half of A's crater, already solid, stays as it was.
  Depositor d(Settings("lip", "cold"));
  d.DepositPass(Straight({0, 0}, {60, 0}, kH, 0));
  auto depth = [&](double y) { return MeanTop(d, 25.0, 35.0, y) - MeanTop(d, 58.0, 59.5, y); };
  const double far_before = depth(-1.5);
  const double near_before = depth(1.5);
  ASSERT_GT(far_before, 0.3) << "bead A must end in a crater";
  d.DepositPass(Straight({0, 0.6 * kW}, {80, 0.6 * kW}, kH, 0));
  const double far_after = depth(-1.5);
  const double near_after = depth(1.5);
  std::printf("crater of A, far side %.2f -> %.2f mm, under B's footprint %.2f -> %.2f mm\n", far_before, far_after,
              near_before, near_after);
  EXPECT_NEAR(far_after, far_before, 1e-9) << "B must not flow into the crater beyond its footprint";
  EXPECT_LT(near_after, near_before - 0.2) << "B's pool fills the part of the crater under its footprint";
}

TEST(ArcStart, ColdStartDrapesOverAValleyTheSteadyPoolLevels) {
  // Two beads 1.2 w apart leave a valley at y = 0; a bead laid on it starts at x = 0. Cold, its first millimetres
  // set on the ground under them (the valley shows through); hot, they level into it. Further on both level alike.
  auto build = [](const std::string& wetting) {
    Depositor d(Settings("lip", wetting));
    d.DepositPass(Straight({0, -0.6 * kW}, {80, -0.6 * kW}, kH, 0));
    d.DepositPass(Straight({80, 0.6 * kW}, {0, 0.6 * kW}, kH, 0));
    d.DepositPass(Straight({0, 0}, {80, 0}, 2.0 * kH, 1));
    return d;
  };
  const Depositor cold = build("cold");
  const Depositor hot = build("hot");
  // Crown over the valley minus the surface 2 mm aside, in the first millimetre of the start.
  auto dip = [](const Depositor& d, double x0, double x1) {
    return 0.5 * (MeanTop(d, x0, x1, -2.0) + MeanTop(d, x0, x1, 2.0)) - MeanTop(d, x0, x1, 0.0);
  };
  std::printf("surface over the valley below its sides at the start: cold %.2f mm, hot %.2f mm\n", dip(cold, 0.5, 1.5),
              dip(hot, 0.5, 1.5));
  EXPECT_GT(dip(cold, 0.5, 1.5), dip(hot, 0.5, 1.5) + 0.2) << "a cold start must not level into the valley";
  EXPECT_NEAR(MeanTop(cold, 30.0, 40.0, 0.0), MeanTop(hot, 30.0, 40.0, 0.0), 2.0 * kVoxel)
      << "past the start length both are the steady, levelled pool";
}

}  // namespace
}  // namespace waam::twin
