// Tests of ear-clipping triangulation with hole bridging: area, orientation and triangle count invariants.
#include "models/core/numbers.h"
#include "planner/geometry/triangulate.h"

#include <cmath>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "planner/mesh/extrude.h"

namespace waam::planner {
namespace {

// Sum of the triangle areas; every triangle must be counter-clockwise (positive area).
double TriangleAreaSum(const PolygonWithHoles& region, const std::vector<std::array<int, 3>>& triangles) {
  std::vector<Eigen::Vector2d> pts(region.outer.begin(), region.outer.end());
  for (const Ring& hole : region.holes) pts.insert(pts.end(), hole.begin(), hole.end());
  double sum = 0.0;
  for (const auto& t : triangles) {
    const double area = SignedArea({pts[t[0]], pts[t[1]], pts[t[2]]});
    EXPECT_GT(area, 0.0) << "triangle " << t[0] << " " << t[1] << " " << t[2] << " is not counter-clockwise";
    sum += area;
  }
  return sum;
}

void ExpectExactCover(const PolygonWithHoles& region) {
  const auto triangles = TriangulateRegion(region);
  std::size_t n = region.outer.size();
  for (const Ring& hole : region.holes) n += hole.size();
  // A polygon with n vertices and h holes has n + 2h - 2 triangles.
  EXPECT_EQ(triangles.size(), n + 2 * region.holes.size() - 2);
  EXPECT_NEAR(TriangleAreaSum(region, triangles), Area(region), 1e-9 * Area(region));
}

TEST(Triangulate, RandomStarPolygonsWithHoles) {
  std::mt19937_64 rng(20140101);
  std::uniform_real_distribution<double> radius(40.0, 100.0);
  for (int trial = 0; trial < 20; ++trial) {
    PolygonWithHoles region;
    const int n = 30 + trial;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * kPi * i / n;
      const double r = radius(rng);
      region.outer.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    // Holes inside the inner radius 40, given counter-clockwise on purpose (the triangulator reorients).
    region.holes.push_back(CircleRing(Eigen::Vector2d(-15, 0), 8, 12));
    region.holes.push_back(CircleRing(Eigen::Vector2d(15, 5), 6, 9));
    region.holes.push_back(RectangleRing(-5, -30, 5, -20));
    ExpectExactCover(region);
  }
}

TEST(Triangulate, GridOfAlignedRectangularHoles) {
  // Collinear hole edges aligned with the outer ring: the case of rib-web cells.
  PolygonWithHoles region{RectangleRing(0, 0, 100, 70), {}};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 3; ++j) region.holes.push_back(RectangleRing(5 + 24 * i, 5 + 21 * j, 24 * (i + 1), 21 * (j + 1)));
  }
  ExpectExactCover(region);
}

TEST(Triangulate, HoleTouchingTheOuterRingIsAnError) {
  PolygonWithHoles region{RectangleRing(0, 0, 100, 70), {RectangleRing(80, 10, 100, 20)}};
  try {
    TriangulateRegion(region);
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("no bridge from the hole at (100, 10) mm"));
  }
}

TEST(Triangulate, ClockwiseOuterIsAccepted) {
  PolygonWithHoles region{{{0, 0}, {0, 10}, {10, 10}, {10, 0}}, {}};
  ExpectExactCover(region);
}

TEST(Triangulate, TooFewPointsIsAnError) {
  PolygonWithHoles region{{{0, 0}, {1, 0}}, {}};
  EXPECT_THROW(TriangulateRegion(region), InputError);
}

}  // namespace
}  // namespace waam::planner
