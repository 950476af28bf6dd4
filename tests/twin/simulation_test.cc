// DepositPlan and MeasureBuild end to end on a small block: volume balance, measures filled in, deviation against the box target.
#include "tests/twin/twin_settings.h"
#include "twin/simulation.h"

#include <gtest/gtest.h>

#include "tests/twin/test_paths.h"

namespace waam::twin {
namespace {

TEST(Simulation, BlockAgainstItsBoxTarget) {
  const double w = 6.0, h = 2.0, l = 0.738 * w;
  const planner::Plan plan = testing::ParallelBlock(testing::BlockPositions(0.5 * w, 0.47 * w, l, 4), 40.0, 3,
                                                    2.0 / 3.0 * w * h / l, w, h, 8.0);
  const auto& region = plan.layers.back().slice.front().outer;
  const planner::TriangleMesh box = testing::BoxMesh({region[0].x(), 0, 0}, {region[1].x(), 40.0, plan.layers.back().z_mm});
  const TwinResult r = MeasureBuild(plan, DepositPlan(plan, twin::TestSimulationSettings(), 100.0, nullptr), &box, w);
  const TwinMeasures& m = r.measures;
  // The build ends with the last pass's arc end: its start time plus its weld time.
  const std::vector<ExecutedPass> passes = ExecutePlan(plan, twin::TestSimulationSettings(), 100.0);
  ASSERT_FALSE(passes.empty());
  const double last_arc_end_s = passes.back().start_time_s + PassTimes(passes.back()).back();
  EXPECT_NEAR(m.build_time_s, last_arc_end_s, 1e-9 * last_arc_end_s);
  EXPECT_EQ(m.layers, 3u);
  EXPECT_EQ(m.beads, 3u * 8u);
  EXPECT_NEAR(m.deposited_volume_mm3, m.expected_volume_mm3, 0.02 * m.expected_volume_mm3);
  EXPECT_GT(r.deviation.samples, 0u);
  EXPECT_LT(r.deviation.min_mm, 0.0) << "bead ripple and rounded edges lie inside a box target";
  EXPECT_GT(r.deviation.max_mm, r.deviation.min_mm);
  EXPECT_GT(m.ra_mm, 0.0);
  EXPECT_GE(m.waviness_mm, m.ra_mm) << "the peak-to-valley bounds the mean deviation";
  // Ding Fig. 13's surface variation, over the same columns as Ra: the mean lies between the lowest and the highest
  // column, Ra is at most half their spread, and three layers stand within a bead height of the plan's top slice
  // (the denser boundary beads, the start humps and the voxel tops put the mean about 1 mm above it here).
  EXPECT_LE(m.top_min_mm, m.top_mean_mm);
  EXPECT_LE(m.top_mean_mm, m.top_max_mm);
  EXPECT_LE(m.ra_mm, 0.5 * (m.top_max_mm - m.top_min_mm) + 1e-9);
  EXPECT_NEAR(m.top_mean_mm, plan.layers.back().z_mm, h)
      << "top min " << m.top_min_mm << " max " << m.top_max_mm << " mm";
  EXPECT_GT(m.build_time_s, 0.0);
}

// The top-surface measures apply to a planar plan only: a tilted build direction, a slice off the horizontal plane,
// a layer whose weld points climb several bead heights, or no top region each give a reason.
TEST(Simulation, TopSurfaceMeasuresApplyToPlanarPlansOnly) {
  const double w = 6.0, h = 2.0, l = 0.738 * w;
  const planner::Plan planar = testing::ParallelBlock(testing::BlockPositions(0.5 * w, 0.47 * w, l, 4), 40.0, 3,
                                                      2.0 / 3.0 * w * h / l, w, h, 8.0);
  EXPECT_EQ(TopSurfaceNotApplicable(planar), "");
  planner::Plan tilted = planar;
  tilted.layers[1].build_dir_P = Eigen::Vector3d(0.0, std::sin(0.1), std::cos(0.1));  // 5.7 deg off +z
  EXPECT_NE(TopSurfaceNotApplicable(tilted).find("multi-directional"), std::string::npos);
  planner::Plan curved = planar;
  curved.layers[0].slice_in_plane = false;
  EXPECT_NE(TopSurfaceNotApplicable(curved).find("non-planar"), std::string::npos);
  planner::Plan climbing = planar;
  for (std::size_t i = 0; i < climbing.layers[2].points.size(); ++i) climbing.layers[2].points[i].p_P.z() += 0.5 * i;
  EXPECT_NE(TopSurfaceNotApplicable(climbing).find("non-planar"), std::string::npos);
  planner::Plan imported = planar;
  imported.layers.back().slice.clear();
  EXPECT_NE(TopSurfaceNotApplicable(imported).find("no sliced region"), std::string::npos);
}

}  // namespace
}  // namespace waam::twin
