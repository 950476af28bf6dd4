// Tests of the notch-elimination convex decomposition and the rotating-calipers minimum width.
#include "planner/geometry/convex_decomposition.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "planner/geometry/clipper_adapter.h"
#include "test_shapes.h"

namespace waam::planner {
namespace {

using ::testing::HasSubstr;
using testing::DingLikeShapes;

// Pieces are convex, tile the region without overlap and their areas sum to the region's.
void ExpectTiling(const PolygonWithHoles& region, const std::string& name) {
  const ConvexDecomposition decomposition = DecomposeConvex(region);
  ASSERT_TRUE(decomposition.ok()) << name << ": " << decomposition.failure;
  const std::vector<Ring>& pieces = decomposition.pieces;
  ASSERT_FALSE(pieces.empty()) << name;
  const double area = Area(region);
  double sum = 0.0;
  std::vector<PolygonWithHoles> as_regions;
  for (const Ring& piece : pieces) {
    EXPECT_TRUE(IsConvex(piece, 1e-7)) << name << ": every piece should be convex";
    EXPECT_GT(SignedArea(piece), 0.0) << name << ": pieces should be counter-clockwise";
    sum += SignedArea(piece);
    as_regions.push_back({piece, {}});
  }
  EXPECT_NEAR(sum, area, 1e-6 * area) << name << ": piece areas should sum to the region area";
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (std::size_t j = i + 1; j < pieces.size(); ++j) {
      const double overlap = Area(internal::Intersection({as_regions[i]}, {as_regions[j]}));
      EXPECT_LT(overlap, 1e-6 * area) << name << ": pieces " << i << " and " << j << " should not overlap";
    }
  }
  // Nothing of the region is left out (Clipper's 0.1 um grid allows a sliver of rounding).
  const double missing = Area(internal::Difference({region}, as_regions));
  EXPECT_LT(missing, 1e-5 * area) << name << ": the pieces should cover the region";
}

TEST(DecomposeConvex, TilesLTAndUShapes) {
  ExpectTiling(testing::LShape(), "L");
  ExpectTiling(testing::TShape(), "T");
  ExpectTiling(testing::UShape(), "U");
  EXPECT_EQ(DecomposeConvex(testing::LShape()).pieces.size(), 2u) << "one notch-line cut splits an L in two";
  EXPECT_EQ(DecomposeConvex(testing::TShape()).pieces.size(), 2u)
      << "notch-notch: one cut along the line through both notches of a T removes both";
}

TEST(DecomposeConvex, ConvexInputIsOnePiece) {
  const std::vector<Ring> pieces = DecomposeConvex({testing::Circle(0, 0, 10, 12), {}}).pieces;
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_NEAR(SignedArea(pieces[0]), SignedArea(testing::Circle(0, 0, 10, 12)), 1e-9);
}

TEST(DecomposeConvex, AcceptsClockwiseOutline) {
  PolygonWithHoles l = testing::LShape();
  std::reverse(l.outer.begin(), l.outer.end());
  ExpectTiling(l, "clockwise L");
}

TEST(DecomposeConvex, TilesPlateWithHoles) { ExpectTiling(testing::PlateWithHoles(), "plate with holes"); }

TEST(DecomposeConvex, TilesDingLikeShapes) {
  for (const auto& [name, region] : DingLikeShapes()) ExpectTiling(region, name);
}

TEST(DecomposeConvex, TilesRandomStars) {
  std::mt19937_64 rng(20240607);
  for (int k = 0; k < 40; ++k) {
    const int n = 6 + k % 25;
    ExpectTiling(testing::RandomStar(rng, n, 50.0), "star " + std::to_string(k) + " (" + std::to_string(n) + ")");
  }
}

TEST(DecomposeConvex, TilesRandomStarsWithAHole) {
  std::mt19937_64 rng(77);
  for (int k = 0; k < 20; ++k) {
    PolygonWithHoles star = testing::RandomStar(rng, 10 + k, 60.0);
    star.holes.push_back(testing::Circle(0.0, 0.0, 8.0, 7 + k % 5, true));  // radii >= 21 mm: the hole is inside
    ExpectTiling(star, "star with hole " + std::to_string(k));
  }
}

TEST(DecomposeConvex, RejectsDegenerateOutline) {
  try {
    DecomposeConvex({testing::Poly({{0, 0}, {1, 0}, {0, 0}}), {}});
    FAIL() << "expected InputError for a two-point outline";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("need >= 3"));
  }
}

// Cutting off the shallow notches of a curved wall: the inner arc's 35 facets become a few chords, the convex outer
// arc stays as it is, the region only grows, and by no more than the depth.
TEST(FillShallowNotches, CurvedWallLosesItsFacetNotchesOnly) {
  const PolygonWithHoles band = testing::ArcBand(60.0, 72.0, 70.0, 35);
  const double depth = 0.6;
  const Ring filled = FillShallowNotches(band.outer, depth);
  EXPECT_LT(filled.size(), band.outer.size() - 25) << "most of the inner arc's notches are cut off";
  EXPECT_GT(SignedArea(filled), 0.0) << "orientation kept";
  for (const Eigen::Vector2d& p : band.outer) {
    if (p.norm() > 66.0) {  // every vertex of the convex outer arc is kept
      const bool kept = std::any_of(filled.begin(), filled.end(),
                                    [&](const Eigen::Vector2d& q) { return (q - p).norm() < 1e-9; });
      EXPECT_TRUE(kept) << "outer arc vertex (" << p.x() << ", " << p.y() << ")";
    }
  }
  const PolygonWithHoles grown{filled, {}};
  EXPECT_LT(Area(internal::Difference({band}, {grown})), 1e-3) << "the region only grows";
  EXPECT_LT(Area(internal::Difference({grown}, internal::Offset({band}, depth + 0.01))), 1e-3)
      << "by no more than the depth";
  EXPECT_GT(DecomposeConvex(band).pieces.size(), 3 * DecomposeConvex(grown).pieces.size())
      << "fewer pieces to decompose";
  const Ring square = testing::Rect(0, 0, 10, 10);
  EXPECT_EQ(FillShallowNotches(square, 5.0), square) << "a convex ring has no notch to cut off";
  EXPECT_THAT([] { FillShallowNotches(testing::Rect(0, 0, 1, 1), -1.0); },
              ::testing::ThrowsMessage<InputError>(::testing::HasSubstr("must be >= 0")));
}

TEST(FindSharedEdges, LShapeSharesItsCut) {
  const PolygonWithHoles l = testing::LShape();
  const std::vector<Ring> pieces = DecomposeConvex(l).pieces;
  const std::vector<SharedEdge> shared = FindSharedEdges(pieces, l);
  ASSERT_EQ(shared.size(), 1u);
  EXPECT_TRUE(shared[0].a_on_boundary);
  EXPECT_LT((shared[0].a - Eigen::Vector2d(40, 40)).norm() * (shared[0].b - Eigen::Vector2d(40, 40)).norm(), 1e-6)
      << "the cut starts at the notch (40, 40)";
}

double WidthAt(const Ring& ring, double angle) {
  const Eigen::Vector2d n(-std::sin(angle), std::cos(angle));
  double lo = 1e300, hi = -1e300;
  for (const auto& p : ring) lo = std::min(lo, n.dot(p)), hi = std::max(hi, n.dot(p));
  return hi - lo;
}

TEST(MinimumWidthDirection, RotatedRectangle) {
  Ring r;
  const double a = 30.0 * std::numbers::pi / 180.0;
  for (const auto& p : testing::Rect(0, 0, 100, 20)) {
    r.emplace_back(std::cos(a) * p.x() - std::sin(a) * p.y(), std::sin(a) * p.x() + std::cos(a) * p.y());
  }
  double width = 0.0;
  EXPECT_NEAR(MinimumWidthDirection(r, &width), a, 1e-12);
  EXPECT_NEAR(width, 20.0, 1e-9);
}

TEST(MinimumWidthDirection, MatchesBruteForceOnRandomConvexPolygons) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> coord(-50.0, 50.0);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<Eigen::Vector2d> points(5 + trial % 30);
    for (auto& p : points) p = Eigen::Vector2d(coord(rng), 0.4 * coord(rng));
    const Ring hull = ConvexHull(points);
    double width = 0.0;
    const double angle = MinimumWidthDirection(hull, &width);
    EXPECT_NEAR(WidthAt(hull, angle), width, 1e-9) << "the reported width is the width at the reported angle";
    // Brute force: fine sampling, then a golden-section refinement around the best sample.
    constexpr int kSamples = 20000;
    double best = 1e300, best_angle = 0.0;
    for (int k = 0; k < kSamples; ++k) {
      const double t = std::numbers::pi * k / kSamples;
      if (WidthAt(hull, t) < best) best = WidthAt(hull, t), best_angle = t;
    }
    double lo = best_angle - std::numbers::pi / kSamples, hi = best_angle + std::numbers::pi / kSamples;
    for (int it = 0; it < 100; ++it) {
      const double m1 = lo + 0.382 * (hi - lo), m2 = lo + 0.618 * (hi - lo);
      (WidthAt(hull, m1) < WidthAt(hull, m2) ? hi : lo) = WidthAt(hull, m1) < WidthAt(hull, m2) ? m2 : m1;
    }
    best = std::min(best, WidthAt(hull, 0.5 * (lo + hi)));
    EXPECT_NEAR(width, best, 1e-7) << "trial " << trial << ": calipers and brute force should agree";
    EXPECT_GE(best, width - 1e-9) << "no direction may be narrower than the calipers' minimum";
  }
}

TEST(MinimumWidthDirection, RejectsCollinearPoints) {
  try {
    MinimumWidthDirection(testing::Poly({{0, 0}, {1, 1}, {2, 2}}), nullptr);
    FAIL() << "expected InputError for collinear points";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("need >= 3"));
  }
}

}  // namespace
}  // namespace waam::planner
