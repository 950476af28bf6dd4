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
    options.pattern = "hybrid";
    const Counts hybrid = Count(PlanLayerPattern({region}, options));
    options.pattern = "continuous";
    const Counts continuous = Count(PlanLayerPattern({region}, options));
    std::printf("| %c | %s | %.0f | %d | %d | %d | %d |\n", name[0], name.substr(2).c_str(), Area(region),
                hybrid.passes, hybrid.elements, continuous.passes, continuous.elements);
    EXPECT_EQ(continuous.passes, 1) << name;
    EXPECT_GT(hybrid.passes, continuous.passes) << name;
  }
}

}  // namespace
}  // namespace waam::planner
