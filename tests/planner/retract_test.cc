// Tests of the arc-off retract / travel / approach between passes (planner/path/retract.h).
#include "models/core/numbers.h"
#include "planner/path/retract.h"

#include <cmath>
#include <vector>

#include <Eigen/Geometry>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "planner/plan_scenario.h"
#include "tests/planner/test_scenarios.h"

namespace waam::planner {
namespace {

using Eigen::Vector3d;
using testing::SmallPropellerWithRetract;
constexpr double kClearance = 15.0;

PathPoint Point(const Vector3d& p, const Vector3d& tool, bool weld) {
  PathPoint q;
  q.p_P = p;
  q.tool_dir_P = tool.normalized();
  q.bead_width_mm = 6.0;
  q.bead_height_mm = 2.0;
  q.speed_mm_s = 8.0;
  q.weld = weld;
  return q;
}

// One layer of a part tilted by 30 deg about y (its build direction leans towards +x): three parallel passes along
// y, each ending where the planner sends the torch straight to the next start.
Plan TiltedLayer() {
  const Vector3d n(std::sin(kPi / 6), 0.0, std::cos(kPi / 6));  // build direction = torch axis
  const Vector3d u = Vector3d::UnitY(), v = n.cross(u);              // in-plane directions
  Plan plan;
  plan.layers.resize(1);
  plan.layers[0].build_dir_P = n;
  for (int pass = 0; pass < 3; ++pass) {
    const Vector3d base = Vector3d(0, 0, 20) + 5.0 * pass * v;
    plan.layers[0].points.push_back(Point(base, n, false));
    plan.layers[0].points.push_back(Point(base + 40.0 * u, n, true));
    plan.layers[0].points.push_back(Point(base + 40.0 * u + 0.5 * v, n, true));
  }
  return plan;
}

struct Flat {
  std::size_t layer;
  std::size_t index;
  const PathPoint* p;
};
std::vector<Flat> Flatten(const Plan& plan) {
  std::vector<Flat> out;
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    for (std::size_t i = 0; i < plan.layers[l].points.size(); ++i) out.push_back({l, i, &plan.layers[l].points[i]});
  }
  return out;
}

// Every arc-off travel of `plan` begins with a lift of `clearance` along the torch axis of the pass's end, ends with
// a descent of `clearance` along the next start's torch axis, and in between keeps (within the 1 % slack of
// retract.cc) at least `clearance` from everything welded before it.
void ExpectRetractedTravels(const Plan& plan, double clearance) {
  const std::vector<Flat> f = Flatten(plan);
  int travels = 0;
  for (std::size_t k = 1; k + 1 < f.size(); ++k) {
    const PathPoint& a = *f[k - 1].p;
    if (!a.weld || f[k].p->weld) continue;
    // a ends a pass: find the next start s (the non-weld point before the next weld point).
    std::size_t s = k;
    while (s + 1 < f.size() && !f[s + 1].p->weld) ++s;
    if (s + 1 == f.size()) break;  // no pass after this one
    ++travels;
    const PathPoint& lift = *f[k].p;
    const PathPoint& start = *f[s].p;
    const PathPoint& approach = *f[s - 1].p;
    ASSERT_LT(k, s - 1) << "a travel has at least a lift and an approach point before the start";
    EXPECT_LT((lift.p_P - (a.p_P + clearance * a.tool_dir_P)).norm(), 1e-9)
        << "the lift after point " << k - 1 << " goes " << clearance << " mm up its torch axis";
    EXPECT_LT((approach.p_P - (start.p_P + clearance * start.tool_dir_P)).norm(), 1e-9)
        << "the descent to point " << s << " comes " << clearance << " mm down its torch axis";
    for (std::size_t j = k + 1; j < s; ++j) {
      const double d = internal::DistanceToWelded(plan, f[s].layer, f[s].index, f[j - 1].p->p_P, f[j].p->p_P,
                                                  2.0 * clearance);
      EXPECT_GE(d, 0.99 * clearance) << "travel move into point " << j << " (layer " << f[j].layer
                                     << ") comes within " << d << " mm of the welded metal";
    }
  }
  EXPECT_GT(travels, 0) << "the plan has travels between passes";
}

TEST(RetractTest, SegmentDistanceMatchesKnownCases) {
  EXPECT_NEAR(internal::SegmentDistance({0, 0, 0}, {10, 0, 0}, {5, -5, 3}, {5, 5, 3}), 3.0, 1e-12) << "crossing";
  EXPECT_NEAR(internal::SegmentDistance({0, 0, 0}, {10, 0, 0}, {0, 2, 0}, {10, 2, 0}), 2.0, 1e-12) << "parallel";
  EXPECT_NEAR(internal::SegmentDistance({0, 0, 0}, {1, 0, 0}, {4, 4, 0}, {4, 4, 0}), 5.0, 1e-12) << "to a point";
  EXPECT_NEAR(internal::SegmentDistance({0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {5, 0, 0}), 2.0, 1e-12) << "collinear";
}

TEST(RetractTest, TiltedPassToPassTravelLiftsAndDescendsAlongTheTorchAxis) {
  Plan plan = TiltedLayer();
  const RetractReport report = AddRetracts(kClearance, &plan);
  EXPECT_EQ(report.travels, 3u) << "the approach to the first pass and two pass-to-pass travels";
  EXPECT_EQ(report.via_top, 0u) << "a straight travel at the clearance over one layer is clear";
  ExpectRetractedTravels(plan, kClearance);
  const std::vector<PathPoint>& points = plan.layers[0].points;
  // approach, start, 2 weld, lift, approach, start, ... , lift after the last pass.
  ASSERT_EQ(points.size(), 3u * 5u);
  EXPECT_LT((points.front().p_P - (points[1].p_P + kClearance * points[1].tool_dir_P)).norm(), 1e-9)
      << "the first pass is approached along its torch axis";
  EXPECT_FALSE(points.back().weld);
  EXPECT_NEAR((points.back().p_P - points[points.size() - 2].p_P).norm(), kClearance, 1e-9)
      << "the last pass ends with the lift";
}

TEST(RetractTest, ZeroClearanceLeavesThePlanAlone) {
  Plan plan = TiltedLayer();
  const Plan before = plan;
  const RetractReport report = AddRetracts(0.0, &plan);
  EXPECT_EQ(report.travels, 0u);
  ASSERT_EQ(plan.layers[0].points.size(), before.layers[0].points.size());
  for (std::size_t i = 0; i < before.layers[0].points.size(); ++i) {
    EXPECT_EQ(plan.layers[0].points[i].p_P, before.layers[0].points[i].p_P) << "point " << i;
  }
}

TEST(RetractTest, SubVolumesBuiltSidewaysAreReachedOverThePart) {
  // Straight from the hub's top to a blade's root would cut the hub's edge: those travels go over the top.
  PlanResult planned = PlanScenario(testing::WithFiles(SmallPropellerWithRetract(0.0)), nullptr);
  const RetractReport report = AddRetracts(kClearance, &planned.plan);
  EXPECT_GE(report.via_top, 4u) << "at least hub -> blade_0 and blade to blade go over the top";
  EXPECT_LT(report.via_top, report.travels) << "travels inside a sub-volume stay straight";
  ExpectRetractedTravels(planned.plan, kClearance);
}

TEST(RetractTest, WeldMovesAreUnchangedAndOnlyTravelGrows) {
  const PlanResult without = PlanScenario(testing::WithFiles(SmallPropellerWithRetract(0.0)), nullptr);
  const PlanResult with = PlanScenario(testing::WithFiles(SmallPropellerWithRetract(kClearance)), nullptr);
  // The weld moves, in order: (from, to) of every arc-on move.
  auto weld_moves = [](const Plan& plan) {
    std::vector<std::pair<Vector3d, Vector3d>> moves;
    double time_s = 0.0;
    const PathPoint* prev = nullptr;
    for (const LayerPath& layer : plan.layers) {
      for (const PathPoint& p : layer.points) {
        if (prev != nullptr && p.weld) {
          moves.emplace_back(prev->p_P, p.p_P);
          time_s += (p.p_P - prev->p_P).norm() / p.speed_mm_s;
        }
        prev = &p;
      }
    }
    return std::make_pair(moves, time_s);
  };
  const auto [a, time_a] = weld_moves(without.plan);
  const auto [b, time_b] = weld_moves(with.plan);
  ASSERT_EQ(a.size(), b.size()) << "same number of weld moves";
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].first, b[i].first) << "weld move " << i << " starts where it did";
    ASSERT_EQ(a[i].second, b[i].second) << "weld move " << i << " ends where it did";
  }
  EXPECT_DOUBLE_EQ(time_a, time_b) << "weld time";
  EXPECT_DOUBLE_EQ(without.stats.weld_length_mm, with.stats.weld_length_mm);
  EXPECT_EQ(without.stats.passes, with.stats.passes);
  EXPECT_EQ(without.stats.path_elements, with.stats.path_elements);
  EXPECT_EQ(without.stats.passes_per_layer, with.stats.passes_per_layer);
  EXPECT_GT(with.stats.travel_length_mm, without.stats.travel_length_mm);
  EXPECT_GT(with.stats.estimated_time_s, without.stats.estimated_time_s);
  ASSERT_EQ(without.plan.layers.size(), with.plan.layers.size());
}

}  // namespace
}  // namespace waam::planner
