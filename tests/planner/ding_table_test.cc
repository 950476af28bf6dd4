// Ding et al. 2014 Table 2 re-measured: passes and weld path elements per layer, hybrid vs continuous.
#include <cstdio>

#include <gtest/gtest.h>

#include "planner/path/layer_pattern.h"
#include "test_shapes.h"

namespace waam::planner {
namespace {

struct Counts {
  int passes = 0;
  int elements = 0;  // weld moves, each a straight segment
};

Counts Count(const std::vector<Move2D>& moves) {
  Counts c;
  for (std::size_t k = 0; k < moves.size(); ++k) {
    if (moves[k].weld && (k == 0 || !moves[k - 1].weld)) ++c.passes;
    if (moves[k].weld) ++c.elements;
  }
  return c;
}

// Prints the table (run with --gtest_filter=DingTable.*) and checks the paper's qualitative claims: the continuous
// method needs one pass per layer where the hybrid needs several.
TEST(DingTable, HybridVersusContinuous) {
  std::printf("| No. | geometry | area mm2 | hybrid passes | hybrid elements | continuous passes | "
              "continuous elements |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const auto& [name, region] : testing::DingLikeShapes()) {
    PatternOptions options;
    options.bead_width_mm = 6.0;
    options.pattern = Pattern::kHybrid;
    const Counts hybrid = Count(PlanLayerPattern({region}, options));
    options.pattern = Pattern::kContinuous;
    const Counts continuous = Count(PlanLayerPattern({region}, options));
    std::printf("| %c | %s | %.0f | %d | %d | %d | %d |\n", name[0], name.substr(2).c_str(), Area(region),
                hybrid.passes, hybrid.elements, continuous.passes, continuous.elements);
    EXPECT_EQ(continuous.passes, 1) << name;
    EXPECT_GT(hybrid.passes, continuous.passes) << name;
  }
}

double WeldLength(const std::vector<Move2D>& moves) {
  double length = 0.0;
  for (std::size_t k = 1; k < moves.size(); ++k) {
    if (moves[k].weld) length += (moves[k].p - moves[k - 1].p).norm();
  }
  return length;
}

// The continuous path lays one pass per layer and not much more bead than the hybrid path on the same outline: the
// area is the same, so a much longer path means beads piled on beads (the twin then shows it as roughness). It may
// lay less: on the 12 mm walls of the comb the hybrid squeezes a raster between its two contour beads (0.70).
// Coverage is checked by ContinuousPattern.CoversTheRegion.
TEST(DingTable, ContinuousLaysAboutTheHybridBeadLength) {
  for (const auto& [name, region] : testing::DingLikeShapes()) {
    PatternOptions options;
    options.bead_width_mm = 6.0;
    options.pattern = Pattern::kHybrid;
    const std::vector<Move2D> hybrid = PlanLayerPattern({region}, options);
    options.pattern = Pattern::kContinuous;
    const std::vector<Move2D> continuous = PlanLayerPattern({region}, options);
    const double ratio = WeldLength(continuous) / WeldLength(hybrid);
    std::printf("%s: continuous / hybrid bead length %.3f, elements %d / %d\n", name.c_str(), ratio,
                Count(continuous).elements, Count(hybrid).elements);
    EXPECT_EQ(Count(continuous).passes, 1) << name;
    EXPECT_LT(ratio, 1.12) << name << ": the continuous path should lay at most ~10 % more bead than the hybrid";
  }
}

}  // namespace
}  // namespace waam::planner
