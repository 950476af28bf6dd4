// Tests of the continuous pattern on convex round parts: one piece, one pass and full coverage on every layer.
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "planner/geometry/clipper_adapter.h"
#include "planner/geometry/convex_decomposition.h"
#include "planner/path/layer_pattern.h"
#include "pattern_checks.h"
#include "test_shapes.h"

namespace waam::planner {
namespace {

constexpr double kRoundW = 6.0;      // bead width, mm
constexpr int kLayers = 41;     // layer_index 0..40: the start point and direction change every layer
constexpr double kJitterMm = 1e-4;  // a sliced mesh's edge points sit up to this far off the edge

struct Shape {
  std::string name;
  PolygonWithHoles region;
  double max_uncovered = 0.0;  // fraction of the area
};

// Convex round parts and the uncovered fraction allowed for each: what a round bead centred w/2 inside the wall
// cannot reach (sharp corners of few-sided polygons, the tips of an ellipse) plus the cusps between raster ends.
std::vector<Shape> RoundShapes() {
  std::vector<Shape> shapes;
  for (double r : {10.0, 20.0, 30.0, 50.0, 75.0, 100.0}) {
    shapes.push_back({"circle r=" + std::to_string(r), {testing::Circle(0, 0, r, 96), {}}, 0.015});
  }
  std::mt19937_64 rng(2014);
  for (double r : {10.0, 15.0, 30.0, 60.0, 100.0}) {
    shapes.push_back({"sliced cylinder r=" + std::to_string(r), {testing::SlicedCylinder(rng, r, 64, kJitterMm), {}},
                      0.015});
  }
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{{50, 20}, {40, 30}, {60, 15}, {100, 25}}) {
    shapes.push_back({"ellipse " + std::to_string(a) + " x " + std::to_string(b),
                      {testing::Ellipse(a, b, 0.1 * a, 96), {}}, 0.02});
  }
  shapes.push_back({"rounded rect 100x60 r10", {testing::RoundedRect(100, 60, 10, 8), {}}, 0.015});
  shapes.push_back({"rounded rect 60x40 r20", {testing::RoundedRect(60, 40, 20, 12), {}}, 0.015});
  shapes.push_back({"rounded rect 30x30 r5", {testing::RoundedRect(30, 30, 5, 6), {}}, 0.015});
  return shapes;
}

// Passes, coverage and staying inside for one region on layers `layers`.
void ExpectOnePassCovered(const std::string& name, const PolygonWithHoles& region, double max_uncovered,
                          const std::vector<int>& layers) {
  const auto inside = internal::Offset({region}, 0.01);
  for (int layer : layers) {
    PatternOptions options;
    options.bead_width_mm = kRoundW;
    options.layer_index = layer;
    const std::vector<Move2D> moves = PlanLayerPattern({region}, options);
    EXPECT_EQ(testing::CountPasses(moves), 1) << name << " layer " << layer << ": a convex part is one loop, one pass";
    const double uncovered = testing::UncoveredFraction(region, moves, kRoundW);
    EXPECT_LT(uncovered, max_uncovered) << name << " layer " << layer << ": uncovered fraction " << uncovered;
    // Staying inside is checked move by move with Clipper: on every eighth layer only, to keep the test fast.
    if (layer % 8 == 0) {
      EXPECT_LT(testing::WeldLengthOutside(moves, inside), 1e-3) << name << " layer " << layer;
    }
  }
}

std::vector<int> AllLayers() {
  std::vector<int> layers(kLayers);
  for (int k = 0; k < kLayers; ++k) layers[k] = k;
  return layers;
}

TEST(RoundParts, DecompositionOfAConvexPolygonIsItself) {
  for (int n = 3; n <= 128; ++n) {
    const Ring ngon = testing::Circle(0, 0, 30, n);
    const std::vector<Ring> pieces = DecomposeConvex({ngon, {}}).pieces;
    ASSERT_EQ(pieces.size(), 1u) << n << "-gon: a convex polygon has no notch to cut";
    EXPECT_EQ(pieces[0].size(), ngon.size()) << n << "-gon: the piece should keep every corner";
    EXPECT_NEAR(SignedArea(pieces[0]), SignedArea(ngon), 1e-9 * SignedArea(ngon)) << n << "-gon";
  }
  for (const Shape& shape : RoundShapes()) {
    const std::vector<Ring> pieces = DecomposeConvex(shape.region).pieces;
    ASSERT_EQ(pieces.size(), 1u) << shape.name << ": points a rounding error off an edge are no notches";
    EXPECT_NEAR(SignedArea(pieces[0]), Area(shape.region), 1e-6 * Area(shape.region)) << shape.name;
  }
}

TEST(RoundParts, ThroughClipperStillOnePiece) {
  // The slice goes through Clipper (its 1e-4 mm grid) before the decomposition, as PlanLayerPattern does.
  for (const Shape& shape : RoundShapes()) {
    for (const PolygonWithHoles& region : internal::Union({shape.region})) {
      EXPECT_EQ(DecomposeConvex(region).pieces.size(), 1u) << shape.name;
    }
  }
}

// Bound for an n-gon of radius 30 mm: < 2.5 % uncovered (a triangle's three 60-degree corners alone leave ~1.6 %).
TEST(RoundParts, RegularPolygonsOnePassEveryLayer) {
  for (int n = 3; n <= 128; ++n) {
    const PolygonWithHoles ngon{testing::Circle(0, 0, 30, n), {}};
    // Two layers per n, so the 126 polygons go through every start index 0..40 several times.
    ExpectOnePassCovered(std::to_string(n) + "-gon", ngon, 0.025, {n % kLayers, (n + 20) % kLayers});
  }
  for (int n : {3, 4, 6, 16, 64, 128}) {
    ExpectOnePassCovered(std::to_string(n) + "-gon", {testing::Circle(0, 0, 30, n), {}}, 0.025, AllLayers());
  }
}

TEST(RoundParts, CirclesEllipsesRoundedRectsOnePassEveryLayer) {
  for (const Shape& shape : RoundShapes()) {
    ExpectOnePassCovered(shape.name, shape.region, shape.max_uncovered, AllLayers());
  }
}

}  // namespace
}  // namespace waam::planner
