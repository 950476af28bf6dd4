// Cross-checks of the Clipper bridge against analytic areas and lengths.
#include "planner/geometry/clipper_adapter.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "test_shapes.h"

namespace waam::planner::internal {
namespace {

TEST(ClipperAdapter, InwardOffsetOfASquare) {
  // Convex corners of an inward offset stay sharp: a 100 mm square inset by 10 mm is an 80 mm square.
  const auto inset = Offset({{testing::Rect(0, 0, 100, 100), {}}}, -10.0);
  ASSERT_EQ(inset.size(), 1u);
  EXPECT_NEAR(Area(inset), 80.0 * 80.0, 1e-3);
}

TEST(ClipperAdapter, OffsetAroundANotchIsRound) {
  // The exact erosion of the L by d: the two eroded legs, whose inner corner sits at (40 - d, 40 - d), plus the part
  // of the square [40 - d, 40]^2 farther than d from the notch (40, 40): (1 - pi/4) d^2. Round-join chords (0.02 mm
  // sagitta) cut into the excluded disc, so Clipper's area is a little larger, by about 2/3 * 0.02 * arc length.
  const double d = 5.0;
  const double exact = (100 - 2 * d) * (40 - 2 * d) + (40 - 2 * d) * 60.0 + (1.0 - std::numbers::pi / 4.0) * d * d;
  const double area = Area(Offset({testing::LShape()}, -d));
  EXPECT_GE(area, exact - 1e-6);
  EXPECT_NEAR(area, exact, 2.0 / 3.0 * kArcToleranceMm * (0.5 * std::numbers::pi * d) * 1.5);
}

TEST(ClipperAdapter, HolesAndIslandsFromPolyTree) {
  // A square with a hole holding an island: two regions, the outer one with one hole.
  const auto regions = Union({{testing::Rect(0, 0, 100, 100), {testing::Rect(20, 20, 80, 80, true)}},
                              {testing::Rect(40, 40, 60, 60), {}}});
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_NEAR(Area(regions), 100.0 * 100.0 - 60.0 * 60.0 + 20.0 * 20.0, 1e-6);
  for (const auto& r : regions) {
    EXPECT_GT(SignedArea(r.outer), 0.0) << "outers come back counter-clockwise";
    for (const auto& h : r.holes) EXPECT_LT(SignedArea(h), 0.0) << "holes come back clockwise";
  }
}

TEST(ClipperAdapter, BooleansAddUp) {
  const std::vector<PolygonWithHoles> a{{testing::Rect(0, 0, 10, 10), {}}}, b{{testing::Rect(5, 5, 15, 15), {}}};
  EXPECT_NEAR(Area(Intersection(a, b)), 25.0, 1e-9);
  EXPECT_NEAR(Area(Difference(a, b)), 75.0, 1e-9);
  EXPECT_NEAR(Area(Union({a[0], b[0]})), 175.0, 1e-9);
}

TEST(ClipperAdapter, OpenPathClipAndBuffer) {
  // A line across a 100 mm square with a 40 mm hole: 60 mm of it lies inside the material, in two pieces.
  const PolygonWithHoles plate{testing::Rect(0, 0, 100, 100), {testing::Rect(30, 30, 70, 70, true)}};
  const auto pieces = ClipPolylines({{{-10, 50}, {110, 50}}}, {plate});
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_NEAR(Length(pieces[0]) + Length(pieces[1]), 60.0, 1e-6);
  // A bead of radius r along a segment of length L covers 2 r L + pi r^2 (round caps drawn with chords of at most
  // 0.02 mm sagitta, which lose about 2/3 * 0.02 * 2 pi r).
  const double r = 3.0, length = 50.0;
  const double area = Area(BufferPolylines({{{0, 0}, {length, 0}}}, r));
  const double chord_loss = 2.0 / 3.0 * kArcToleranceMm * 2 * std::numbers::pi * r;
  EXPECT_NEAR(area, 2 * r * length + std::numbers::pi * r * r, 1.5 * chord_loss);
  EXPECT_LT(area, 2 * r * length + std::numbers::pi * r * r) << "chords lie inside the true disc";
}

}  // namespace
}  // namespace waam::planner::internal
