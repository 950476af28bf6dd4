// Surface measures and the reproductions of the block experiment (003 Table 9, Fig. 24) and Ding's Ra comparison.
#include "tests/twin/twin_settings.h"
#include "models/core/numbers.h"
#include "twin/scanner/surface_metrics.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "tests/twin/test_paths.h"
#include "twin/deposition/bead_deposition.h"

namespace waam::twin {
namespace {

using ::testing::HasSubstr;
using testing::AddPass;

TEST(SurfaceMetrics, RaOfKnownHeights) {
  EXPECT_NEAR(ArithmeticRoughness({1.0, 3.0, 1.0, 3.0}), 1.0, 1e-12);
  EXPECT_NEAR(ArithmeticRoughness({2.0, 2.0}), 0.0, 1e-12);
  std::vector<ProfileSample> p = {{0, 1.0}, {1, 4.0}, {2, NAN}, {3, 0.5}};
  EXPECT_NEAR(Waviness(p), 3.5, 1e-12);
}

TEST(SurfaceMetrics, BoundaryLagNeedsPositiveWidth) {
  HeightMap map;
  try {
    MeasureBoundaryLag(map, {}, 0.0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bead width"));
  }
}

// A 9 mm wall 6 mm beads wide has no column 1.5 w from its outline: the lag is not measured (NaN), not the negative
// of the boundary's height.
TEST(SurfaceMetrics, BoundaryLagOfAThinWallIsNotMeasured) {
  HeightMap map;
  map.voxel_mm = 0.5;
  map.nx = 100;
  map.ny = 18;
  map.top_mm.assign(static_cast<std::size_t>(map.nx) * map.ny, 10.0f);
  const planner::PolygonWithHoles wall{{{0, 0}, {50, 0}, {50, 9}, {0, 9}}, {}};
  const BoundaryLag lag = MeasureBoundaryLag(map, {wall}, 6.0);
  EXPECT_EQ(lag.interior_columns, 0u);
  EXPECT_GT(lag.boundary_columns, 0u);
  EXPECT_NEAR(lag.boundary_mean_mm, 10.0, 1e-6);
  EXPECT_TRUE(std::isnan(lag.lag_mm)) << "got " << lag.lag_mm;
}

// One row of Table 9 (003): wire feed and travel speed in mm/min, bead width and the spacings in mm.
struct Table9Row {
  double wire_feed = 0, travel = 0, w = 0, l = 0, d1 = 0, d2 = 0;
};
std::vector<Table9Row> ReadTable9() {
  std::ifstream in(std::string(WAAM_SOURCE_DIR) + "/models/data/nguyen2022_table9_overlap.csv");
  std::vector<Table9Row> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'n') continue;
    std::vector<double> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(std::stod(cell));
    if (f.size() >= 7) rows.push_back({f[1], f[2], f[3], f[4], f[5], f[6]});
  }
  return rows;
}

struct BlockResult {
  BoundaryLag lag;
  double deposited = 0.0;
  double expected = 0.0;
};
// Seven layers of straight beads 60 mm long with 6 zigzag beads between two contour beads on each side (003 Fig. 22
// seen in the section across the long edges); h from eq. 3.4 with a 1.0 mm wire.
BlockResult SimulateBlock(const Table9Row& row, double d2, double d1, double l) {
  const double w = row.w;
  const double vt = row.travel / 60.0;
  const double h = 3.0 * kPi * row.wire_feed * 1.0 / (8.0 * w * row.travel);  // eq. 3.4
  const double length = 60.0;
  const std::vector<double> xs = testing::BlockPositions(d2, d1, l, 6);
  const planner::Plan plan = testing::ParallelBlock(xs, length, 7, 2.0 / 3.0 * w * h / l, w, h, vt);
  twin::SimulationSettings s = twin::TestSimulationSettings();
  s.voxel_mm = 0.5;
  const Depositor d = DepositPlan(plan, s, 100.0, nullptr);
  const HeightMap map = TopHeightMap(d.grid());
  BlockResult r;
  r.lag = MeasureBoundaryLag(map, plan.layers.back().slice, w,
                             {Eigen::Vector2d(xs.front() - w, length / 2), Eigen::Vector2d(xs.back() + w, length / 2)});
  r.deposited = d.grid().OccupiedVolume();
  r.expected = d.expected_volume_mm3();
  return r;
}

TEST(SurfaceMetrics, BlockExperimentBoundaryLag) {
  const std::vector<Table9Row> rows = ReadTable9();
  ASSERT_EQ(rows.size(), 3u) << "expected the three rows of Table 9 in models/data";
  for (const Table9Row& row : rows) {
    // Existing model: 0.738 w everywhere; proposed: d2 = 0.5 w, d1 = 0.47 w, l = 0.738 w (eq. 3.15, 3.17).
    const BlockResult existing = SimulateBlock(row, row.l, row.l, row.l);
    const BlockResult proposed = SimulateBlock(row, row.d2, row.d1, row.l);
    std::printf("Table 9 v_w %.0f v_t %.0f w %.2f: boundary lag after 7 layers existing %.2f mm, proposed %.2f mm "
                "(paper, row 1: about 2.7 mm vs an even profile)\n",
                row.wire_feed, row.travel, row.w, existing.lag.lag_mm, proposed.lag.lag_mm);
    EXPECT_NEAR(existing.deposited, existing.expected, 0.02 * existing.expected);
    EXPECT_NEAR(proposed.deposited, proposed.expected, 0.02 * proposed.expected);
    EXPECT_GT(existing.lag.lag_mm, 1.0) << "with 0.738 w everywhere the boundary must end clearly lower";
    EXPECT_LT(std::abs(proposed.lag.lag_mm), 0.5 * existing.lag.lag_mm)
        << "the proposed spacings must leave a fraction of the existing lag";
  }
}

// Ding et al. Fig. 12: one continuous pass per layer gives a top surface with Ra more than 50 % lower than the hybrid
// path with its many starts and stops. Same square, same beads, same spacings; only the number of passes differs.
TEST(SurfaceMetrics, ContinuousPathIsSmootherThanManyStarts) {
  const double w = 6.0, h = 2.0, a = 50.0;
  twin::SimulationSettings s = twin::TestSimulationSettings();
  s.voxel_mm = 0.25;
  double ra[2] = {0, 0};
  std::size_t passes[2] = {0, 0};
  for (int continuous = 0; continuous < 2; ++continuous) {
    const planner::Plan plan = testing::SquareLayers(a, 3, w, h, 0.738 * w, 0.47 * w, 8.0, continuous == 1);
    const Depositor d = DepositPlan(plan, s, 100.0, nullptr);
    EXPECT_NEAR(d.grid().OccupiedVolume(), d.expected_volume_mm3(), 0.02 * d.expected_volume_mm3());
    const HeightMap map = TopHeightMap(d.grid());
    ra[continuous] = ArithmeticRoughness(RegionHeights(map, plan.layers.back().slice, w));
    passes[continuous] = d.beads().size();
  }
  std::printf("square %.0f mm, 3 layers: Ra continuous (%zu passes) %.3f mm, many starts (%zu passes) %.3f mm, "
              "%.0f %% lower (Ding: more than 50 %% lower)\n", a, passes[1], ra[1], passes[0], ra[0],
              100.0 * (1.0 - ra[1] / ra[0]));
  // The twin reproduces the direction but not Ding's size: the ripple between overlapped parabolic caps, the same in
  // both plans, dominates Ra here (see the report). Asserted: clearly lower, by at least 15 %.
  EXPECT_LT(ra[1], 0.85 * ra[0]) << "one continuous pass must give a clearly lower Ra than many starts";
}

}  // namespace
}  // namespace waam::twin
