// AppendBeadOutlines and AreaOutsideBeads against Clipper's own offset and difference.
#include "planner/geometry/bead_outline.h"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "test_shapes.h"

namespace waam::planner::internal {
namespace {

// Area of `region` outside the beads of `lines`: through Clipper's open round offset, then a difference.
double ClipperReference(const std::vector<PolygonWithHoles>& region, const std::vector<Polyline>& lines, double r,
                        double tolerance) {
  return Area(Difference(region, BufferPolylines(lines, r, tolerance)));
}

double Outlined(const std::vector<PolygonWithHoles>& region, const std::vector<Polyline>& lines, double r,
                double tolerance) {
  ClipperLib::Paths outlines;
  AppendBeadOutlines(lines, r, tolerance, &outlines);
  return AreaOutsideBeads(ToPaths(region), outlines);
}

// Smooth rings (the contour pattern's case: every inner join mitred), sharp zigzags and hairpins (Clipper's loop
// kept), a single point, repeated points and a two-point move: the same uncovered area as Clipper's offset.
TEST(BeadOutline, SameAreaAsClippersOffset) {
  const std::vector<PolygonWithHoles> region = {{testing::Circle(0, 0, 60, 400), {testing::Circle(0, 0, 15, 60, true)}}};
  std::vector<Polyline> lines;
  for (double radius = 20.0; radius < 58.0; radius += 2.2) {  // rings 2.2 mm apart, beads 2 mm wide: gaps between
    Polyline ring;
    for (int k = 0; k <= 300; ++k) {
      const double a = 2.0 * std::numbers::pi * k / 300;
      ring.emplace_back(radius * std::cos(a), radius * std::sin(a));
    }
    lines.push_back(ring);
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-55.0, 55.0);
  for (int n = 0; n < 20; ++n) {  // random walks: turns of every angle, hairpins included
    Polyline walk = {{coord(rng), coord(rng)}};
    for (int k = 0; k < 30; ++k) walk.push_back(walk.back() + Eigen::Vector2d(0.2 * coord(rng), 0.2 * coord(rng)));
    lines.push_back(walk);
  }
  lines.push_back({{3.0, 3.0}, {3.0, 3.0}});                           // a move on the spot
  lines.push_back({{-40.0, 0.0}, {-40.0, 0.0}, {-30.0, 1.0}, {-30.0, 1.0}, {-20.0, 0.0}});  // repeated points
  for (const double tolerance : {0.01, 0.05}) {
    const double reference = ClipperReference(region, lines, 1.0, tolerance);
    const double outlined = Outlined(region, lines, 1.0, tolerance);
    EXPECT_GT(reference, 100.0) << "the test leaves part of the region bare";
    EXPECT_NEAR(outlined, reference, 1e-6 * Area(region)) << "arc tolerance " << tolerance << " mm";
  }
}

// Every join of a smooth ring on its inner side becomes one point: with the two of each round join on the outer side
// a ring of n points makes an outline of about 3n points plus the caps, where Clipper's offset makes 5n (3 per
// inner join) before its union.
TEST(BeadOutline, SmoothRingHasOnePointPerInnerJoin) {
  Polyline ring;
  const int n = 1000;
  for (int k = 0; k <= n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    ring.emplace_back(100.0 * std::cos(a), 100.0 * std::sin(a));
  }
  ClipperLib::Paths outlines;
  AppendBeadOutlines({ring}, 1.0, 0.01, &outlines);
  ASSERT_EQ(outlines.size(), 1u);
  EXPECT_LT(outlines[0].size(), static_cast<std::size_t>(3 * n + 100));
  EXPECT_GT(ClipperLib::Area(outlines[0]), 0.0) << "outlines wind positively";
}

TEST(BeadOutline, EmptyAndZeroRadius) {
  ClipperLib::Paths outlines;
  AppendBeadOutlines({}, 1.0, 0.01, &outlines);
  AppendBeadOutlines({{{0, 0}, {1, 0}}}, 0.0, 0.01, &outlines);
  AppendBeadOutlines({{{0, 0}}}, 1.0, 0.01, &outlines);  // one point: no move, no bead
  EXPECT_TRUE(outlines.empty());
  const std::vector<PolygonWithHoles> square = {{testing::Rect(0, 0, 10, 10), {}}};
  EXPECT_NEAR(AreaOutsideBeads(ToPaths(square), outlines), 100.0, 1e-9);
}

}  // namespace
}  // namespace waam::planner::internal
