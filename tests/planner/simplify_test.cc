// Ring simplification to a tolerance: the kept points, the distance to the input, and valid regions afterwards.
#include "planner/geometry/simplify.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "models/core/numbers.h"
#include "planner/geometry/clipper_adapter.h"

namespace waam::planner {
namespace {

using Vec = Eigen::Vector2d;

// A circle of `n` points, radius r around c, counter-clockwise (clockwise when `hole`), each point moved radially
// by up to `jitter` (seeded).
Ring Circle(const Vec& c, double r, int n, double jitter, bool hole, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  Ring ring;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * kPi * i / n * (hole ? -1.0 : 1.0);
    const double rr = r + u(rng);
    ring.push_back(c + rr * Vec(std::cos(a), std::sin(a)));
  }
  return ring;
}

double SegmentDistance(const Vec& p, const Vec& a, const Vec& b) {
  const double l2 = (b - a).squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((p - a).dot(b - a) / l2, 0.0, 1.0) : 0.0;
  return (a + t * (b - a) - p).norm();
}

double DistanceToRing(const Vec& p, const Ring& ring) {
  double best = 1e300;
  for (std::size_t i = 0; i < ring.size(); ++i) best = std::min(best, SegmentDistance(p, ring[i], ring[(i + 1) % ring.size()]));
  return best;
}

TEST(SimplifyRing, EveryDroppedPointLiesWithinTheToleranceAndFewPointsStay) {
  // A 160 mm circle cut at 2448 facets, like a fine torus slice: at 0.02 mm a chord may span about 5 mm.
  const Ring ring = Circle(Vec::Zero(), 160.0, 2448, 0.0, false);
  const double tolerance = 0.02;
  const Ring simple = SimplifyRing(ring, tolerance);
  EXPECT_EQ(simple.front(), ring.front()) << "the first point is an anchor";
  for (const Vec& p : ring) EXPECT_LE(DistanceToRing(p, simple), tolerance + 1e-12);
  // Chords of sagitta 0.02 mm on r = 160 mm are sqrt(8 r t) = 5.06 mm: at least 2 pi r / 5.06 = 199 of them, and RDP
  // keeps no more than about twice that.
  EXPECT_GE(simple.size(), 199u);
  EXPECT_LE(simple.size(), 2u * 200u) << "from " << ring.size() << " points";
  EXPECT_NEAR(SignedArea(simple), SignedArea(ring), Perimeter(ring) * tolerance);
}

TEST(SimplifyRing, SmallRingsAndZeroToleranceComeBackUnchanged) {
  const Ring triangle = {Vec(0, 0), Vec(1, 0), Vec(0, 1)};
  EXPECT_EQ(SimplifyRing(triangle, 10.0), triangle);
  const Ring fine = Circle(Vec::Zero(), 10.0, 100, 0.0, false);
  EXPECT_EQ(SimplifyRing(fine, 0.0), fine);
}

TEST(SimplifyRegions, ResultIsValidHolesStayInsideAndTheAreaMovesLessThanPerimeterTimesTolerance) {
  // A jittered disc with two holes, one of them 0.01 mm from the outer ring: at 0.05 mm the simplified rings may
  // cross there, and the clean-up must still give valid regions.
  PolygonWithHoles region;
  region.outer = Circle(Vec::Zero(), 50.0, 3000, 0.03, false, 1);
  region.holes.push_back(Circle(Vec(10.0, 0.0), 15.0, 1500, 0.03, true, 2));
  region.holes.push_back(Circle(Vec(-40.0, 0.0), 9.99 - 0.03, 800, 0.0, true, 3));
  const double tolerance = 0.05;
  const std::vector<PolygonWithHoles> simple = SimplifyRegions({region}, tolerance);
  ASSERT_FALSE(simple.empty());
  double perimeter = Perimeter(region.outer);
  for (const Ring& hole : region.holes) perimeter += Perimeter(hole);
  EXPECT_NEAR(Area(simple), Area(region), perimeter * tolerance);
  // The symmetric difference is a band along the boundaries no wider than the tolerance.
  const double changed = Area(internal::Difference(simple, {region})) + Area(internal::Difference({region}, simple));
  EXPECT_LE(changed, perimeter * tolerance);
  std::size_t points_in = region.outer.size(), points_out = 0;
  for (const Ring& hole : region.holes) points_in += hole.size();
  for (const PolygonWithHoles& r : simple) {
    EXPECT_GT(SignedArea(r.outer), 0.0) << "outer counter-clockwise";
    points_out += r.outer.size();
    for (const Ring& hole : r.holes) {
      EXPECT_LT(SignedArea(hole), 0.0) << "hole clockwise";
      for (const Vec& p : hole) EXPECT_TRUE(PointInRing(p, r.outer) || DistanceToRing(p, r.outer) < 1e-3);
      points_out += hole.size();
    }
  }
  EXPECT_LT(points_out * 2, points_in) << "the jitter is below the tolerance: most points go";
  // Valid: a union of the result changes nothing (no self-intersection or overlap left for Clipper to resolve).
  EXPECT_NEAR(Area(internal::Union(simple)), Area(simple), 1e-6 * Area(simple));
  for (const Vec& p : region.outer) {
    double best = 1e300;
    for (const PolygonWithHoles& r : simple) best = std::min(best, DistanceToRing(p, r.outer));
    EXPECT_LE(best, tolerance + 2e-4) << "every input point of the outer ring near the simplified one (+ Clipper's grid)";
  }
}

TEST(SimplifyRegions, ATwistedRingLosesItsFlippedLobeAndKeepsItsArea) {
  // A bow tie: its left lobe winds positively, its right lobe negatively; only the left one is material.
  PolygonWithHoles bow;
  bow.outer = {Vec(0, 0), Vec(10, 10), Vec(10, 0), Vec(0, 10)};
  const std::vector<PolygonWithHoles> out = SimplifyRegions({bow}, 0.01);
  // ToPath makes the ring's net area positive; the bow tie's net area is 0, so either lobe may be the positive one.
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(Area(out), 25.0, 1e-6);
}

}  // namespace
}  // namespace waam::planner
