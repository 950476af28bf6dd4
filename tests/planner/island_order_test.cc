// Tests of path.island_order (planner/timeline/island_order.h): permutations of a layer's passes, deterministic.
#include "planner/timeline/island_order.h"

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

namespace waam::planner {
namespace {

// A square region of side 20 mm centred at (cx, 0).
PolygonWithHoles Square(double cx) {
  PolygonWithHoles r;
  r.outer = {{cx - 10, -10}, {cx + 10, -10}, {cx + 10, 10}, {cx - 10, 10}};
  return r;
}

// `layers` layers of three islands at x = 0, 50, 100, each with two passes (planned in the order `order`).
Plan ThreeIslands(int layers, const std::vector<int>& order = {0, 1, 2}) {
  Plan plan;
  for (int l = 0; l < layers; ++l) {
    LayerPath layer;
    layer.index = l;
    layer.z_mm = 2.0 * (l + 1);
    for (int k = 0; k < 3; ++k) layer.slice.push_back(Square(50.0 * k));
    for (int k : order) {
      for (int pass = 0; pass < 2; ++pass) {
        const double y = pass == 0 ? -5.0 : 5.0;
        PathPoint start;
        start.p_P = Eigen::Vector3d(50.0 * k - 8, y, layer.z_mm);
        start.bead_width_mm = 4.0;
        PathPoint end = start;
        end.p_P.x() += 16.0;
        end.weld = true;
        end.speed_mm_s = 8.0;
        layer.points.push_back(start);
        layer.points.push_back(end);
      }
    }
    plan.layers.push_back(layer);
  }
  return plan;
}

// The island (0, 1, 2 by x) each pass of a layer starts in, in visiting order.
std::vector<int> IslandSequence(const LayerPath& layer) {
  std::vector<int> seq;
  for (const PathPoint& p : layer.points) {
    if (!p.weld) seq.push_back(static_cast<int>(std::lround((p.p_P.x() + 8.0) / 50.0)));
  }
  return seq;
}

// Same points as `a`, in any order (a valid permutation of whole passes).
void ExpectPermutation(const LayerPath& a, const LayerPath& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  auto key = [](const LayerPath& layer) {
    std::vector<std::array<double, 4>> k;
    for (std::size_t i = 0; i + 1 < layer.points.size(); i += 2) {
      k.push_back({layer.points[i].p_P.x(), layer.points[i].p_P.y(), layer.points[i + 1].p_P.x(),
                   layer.points[i + 1].p_P.y()});
    }
    std::sort(k.begin(), k.end());
    return k;
  };
  EXPECT_EQ(key(a), key(b)) << "the layer's passes are the same, each whole";
  for (std::size_t i = 0; i < b.points.size(); ++i) EXPECT_EQ(b.points[i].weld, i % 2 == 1);
}

TEST(IslandOrderTest, AsPlannedChangesNothing) {
  Plan plan = ThreeIslands(3);
  const Plan before = plan;
  const IslandOrderReport r = OrderIslands(IslandOrder::kAsPlanned, TimelineSettings{}, &plan);
  EXPECT_EQ(r.layers_reordered, 0u);
  for (std::size_t l = 0; l < plan.layers.size(); ++l) EXPECT_EQ(IslandSequence(plan.layers[l]), IslandSequence(before.layers[l]));
}

TEST(IslandOrderTest, RoundRobinStartsConsecutiveLayersAtDifferentIslands) {
  Plan plan = ThreeIslands(4);
  const Plan before = plan;
  const IslandOrderReport r = OrderIslands(IslandOrder::kRoundRobin, TimelineSettings{}, &plan);
  EXPECT_EQ(r.max_units, 3u) << "three islands of two passes each";
  EXPECT_EQ(IslandSequence(plan.layers[0]), (std::vector<int>{0, 0, 1, 1, 2, 2}));
  EXPECT_EQ(IslandSequence(plan.layers[1]), (std::vector<int>{1, 1, 2, 2, 0, 0}));
  EXPECT_EQ(IslandSequence(plan.layers[2]), (std::vector<int>{2, 2, 0, 0, 1, 1}));
  EXPECT_EQ(IslandSequence(plan.layers[3]), (std::vector<int>{0, 0, 1, 1, 2, 2}));
  for (std::size_t l = 0; l < plan.layers.size(); ++l) ExpectPermutation(before.layers[l], plan.layers[l]);
  Plan again = ThreeIslands(4);
  OrderIslands(IslandOrder::kRoundRobin, TimelineSettings{}, &again);
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    EXPECT_EQ(IslandSequence(plan.layers[l]), IslandSequence(again.layers[l])) << "deterministic";
  }
}

TEST(IslandOrderTest, CoolestFirstVisitsTheIslandDepositedLongestAgoFirst) {
  // Layer 0 planned 0, 1, 2; layer 1 planned 2, 1, 0 (the planner starting where the last layer ended): island 0
  // was deposited longest ago, so it goes first, then 1, then 2.
  Plan plan = ThreeIslands(1);
  const Plan second = ThreeIslands(2, {2, 1, 0});
  plan.layers.push_back(second.layers[1]);
  const Plan before = plan;
  const IslandOrderReport r = OrderIslands(IslandOrder::kCoolestFirst, TimelineSettings{}, &plan);
  EXPECT_EQ(r.layers_reordered, 1u);
  EXPECT_EQ(IslandSequence(plan.layers[0]), (std::vector<int>{0, 0, 1, 1, 2, 2})) << "first layer as planned";
  EXPECT_EQ(IslandSequence(plan.layers[1]), (std::vector<int>{0, 0, 1, 1, 2, 2}));
  ExpectPermutation(before.layers[1], plan.layers[1]);
}

TEST(IslandOrderTest, OneRegionReordersItsPasses) {
  // A single region with three passes: the passes are the units.
  Plan plan = ThreeIslands(2);
  for (LayerPath& layer : plan.layers) {
    layer.slice.clear();
    PolygonWithHoles big;
    big.outer = {{-20, -20}, {120, -20}, {120, 20}, {-20, 20}};
    layer.slice.push_back(big);
  }
  const Plan before = plan;
  const IslandOrderReport r = OrderIslands(IslandOrder::kRoundRobin, TimelineSettings{}, &plan);
  EXPECT_EQ(r.max_units, 6u);
  EXPECT_EQ(r.layers_reordered, 1u) << "layer 1 starts at its second pass";
  ExpectPermutation(before.layers[1], plan.layers[1]);
  EXPECT_EQ(plan.layers[1].points[0].p_P, before.layers[1].points[2].p_P);
}

}  // namespace
}  // namespace waam::planner
