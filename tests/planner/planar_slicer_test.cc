// Tests of the planar slicer: areas against analytic values, closed and oriented rings, hole nesting, open chains.
#include "models/core/numbers.h"
#include "planner/slicing/planar_slicer.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "planner/mesh/extrude.h"
#include "planner/mesh/generators.h"
#include "planner/mesh/mesh_ops.h"

namespace waam::planner {
namespace {

using ::testing::HasSubstr;

// Every ring has >= 3 distinct consecutive points, outer rings are CCW and holes CW, holes lie inside their outer.
void ExpectWellFormed(const std::vector<PolygonWithHoles>& slice, double z) {
  for (const PolygonWithHoles& region : slice) {
    ASSERT_GE(region.outer.size(), 3u) << "z = " << z;
    EXPECT_GT(SignedArea(region.outer), 0.0) << "outer ring must be counter-clockwise at z = " << z;
    for (std::size_t i = 0; i < region.outer.size(); ++i) {
      EXPECT_NE(region.outer[i], region.outer[(i + 1) % region.outer.size()]) << "repeated point at z = " << z;
    }
    for (const Ring& hole : region.holes) {
      ASSERT_GE(hole.size(), 3u);
      EXPECT_LT(SignedArea(hole), 0.0) << "hole must be clockwise at z = " << z;
      EXPECT_TRUE(PointInRing(hole.front(), region.outer)) << "hole outside its outer ring at z = " << z;
    }
  }
}

TEST(PlanarSlicer, BoxSlicesAreExactRectangles) {
  const TriangleMesh box = GeneratePart("box", {{"size_mm", {100, 60, 40}}}, "test");
  const std::vector<double> heights = {0.5, 10.0, 20.0, 39.5};
  const auto slices = SlicePlanar(box, heights);
  ASSERT_EQ(slices.size(), heights.size());
  for (std::size_t i = 0; i < heights.size(); ++i) {
    ASSERT_EQ(slices[i].size(), 1u) << "z = " << heights[i];
    EXPECT_TRUE(slices[i][0].holes.empty());
    EXPECT_NEAR(Area(slices[i]), 6000.0, 1e-9);
    ExpectWellFormed(slices[i], heights[i]);
  }
}

TEST(PlanarSlicer, PlanesThroughVerticesFollowTheAboveRule) {
  // A vertex at z == h counts as above: the top face belongs to the section, the bottom face does not.
  const TriangleMesh box = GeneratePart("box", {{"size_mm", {10, 10, 10}}}, "test");
  const auto slices = SlicePlanar(box, {0.0, 10.0, -1.0, 11.0});
  EXPECT_TRUE(slices[0].empty()) << "plane through the bottom face";
  EXPECT_NEAR(Area(slices[1]), 100.0, 1e-12) << "plane through the top face";
  EXPECT_TRUE(slices[2].empty());
  EXPECT_TRUE(slices[3].empty());
  // Sphere planes exactly through latitude rings: the section is the ring polygon itself, closed, no repeats.
  const int segments = 48, rings = 24;
  const double r = 30.0;
  const TriangleMesh sphere = GeneratePart(
      "sphere", {{"radius_mm", {r}}, {"segments", {double(segments)}}, {"rings", {double(rings)}}}, "test");
  for (int k : {3, 12, 20}) {
    const double lat = -kPi / 2 + kPi * k / rings;
    const double z = sphere.vertices[1 + (k - 1) * segments].z();
    const auto slice = SlicePlanar(sphere, {z}).front();
    ASSERT_EQ(slice.size(), 1u) << "k = " << k;
    ExpectWellFormed(slice, z);
    EXPECT_EQ(slice[0].outer.size(), static_cast<std::size_t>(segments));
    const double rho = r * std::cos(lat);
    EXPECT_NEAR(Area(slice), 0.5 * segments * rho * rho * std::sin(2 * kPi / segments), 1e-9 * rho * rho);
  }
}

TEST(PlanarSlicer, CylinderSliceIsTheRegularPolygon) {
  const TriangleMesh cylinder =
      GeneratePart("cylinder", {{"radius_mm", {25}}, {"height_mm", {80}}, {"segments", {128}}}, "test");
  const double exact = 0.5 * 128 * 25 * 25 * std::sin(2 * kPi / 128);
  for (const auto& slice : SlicePlanar(cylinder, {1.0, 33.3, 79.0})) {
    EXPECT_NEAR(Area(slice), exact, 1e-9 * exact);
    EXPECT_NEAR(Area(slice), kPi * 25 * 25, 0.005 * kPi * 25 * 25) << "and within 0.5 % of the circle";
  }
}

TEST(PlanarSlicer, SphereSlicesMatchCircleAreasWithinHalfAPercent) {
  const double r = 50.0;
  const TriangleMesh sphere =
      GeneratePart("sphere", {{"radius_mm", {r}}, {"segments", {256}}, {"rings", {128}}}, "test");
  const std::vector<double> heights = {12.0, 30.0, 50.0, 71.3, 88.0};
  SliceReport report;
  const auto slices = SlicePlanar(sphere, heights, &report);
  for (std::size_t i = 0; i < heights.size(); ++i) {
    const double d = heights[i] - r;
    const double exact = kPi * (r * r - d * d);
    ASSERT_EQ(slices[i].size(), 1u);
    ExpectWellFormed(slices[i], heights[i]);
    EXPECT_NEAR(Area(slices[i]) / exact, 1.0, 0.005) << "z = " << heights[i];
  }
  EXPECT_EQ(report.open_chains, 0u);
  EXPECT_LT(report.facet_tests, sphere.facets.size()) << "the active set must not test every facet at every height";
}

TEST(PlanarSlicer, TorusSlicesAreAnnuliWithOneHole) {
  const double major = 50.0, minor = 15.0;
  const TriangleMesh torus = GeneratePart("torus", {{"major_radius_mm", {major}}, {"minor_radius_mm", {minor}},
                                                    {"major_segments", {256}}, {"minor_segments", {128}}},
                                          "test");
  for (double z : {3.0, 10.0, 15.0, 22.2, 27.0}) {
    const auto slice = SlicePlanar(torus, {z}).front();
    ASSERT_EQ(slice.size(), 1u) << "z = " << z;
    ASSERT_EQ(slice[0].holes.size(), 1u) << "z = " << z;
    ExpectWellFormed(slice, z);
    const double s = std::sqrt(minor * minor - (z - minor) * (z - minor));
    const double exact = 4 * kPi * major * s;  // pi ((R + s)^2 - (R - s)^2)
    EXPECT_NEAR(Area(slice) / exact, 1.0, 0.005) << "z = " << z;
  }
}

TEST(PlanarSlicer, PlateWithHolesNestsEveryHole) {
  const TriangleMesh plate = GeneratePart("plate_with_holes", {}, "test");
  const auto slice = SlicePlanar(plate, {6.0}).front();
  ASSERT_EQ(slice.size(), 1u);
  EXPECT_EQ(slice[0].holes.size(), 3u);
  ExpectWellFormed(slice, 6.0);
  EXPECT_NEAR(Area(slice) * 12.0, EnclosedVolume(plate), 1e-9 * EnclosedVolume(plate));
}

TEST(PlanarSlicer, HollowBoxWithAnIslandGivesAnOuterWithAHoleAndANewOuter) {
  // A 100 mm cube with a closed 60 mm cavity (inward facets) holding a floating 20 mm cube: depths 0, 1, 2.
  TriangleMesh part = GeneratePart("box", {{"size_mm", {100, 100, 100}}}, "test");
  TriangleMesh cavity = GeneratePart("box", {{"size_mm", {60, 60, 60}}}, "test");
  for (auto& f : cavity.facets) std::swap(f[1], f[2]);
  Translate(&cavity, Eigen::Vector3d(0, 0, 20));
  TriangleMesh island = GeneratePart("box", {{"size_mm", {20, 20, 20}}}, "test");
  Translate(&island, Eigen::Vector3d(0, 0, 40));
  AppendMesh(cavity, &part);
  AppendMesh(island, &part);
  const MeshReport report = InspectMesh(part, 0.0, "hollow box");
  ASSERT_TRUE(report.watertight);
  EXPECT_NEAR(report.volume_mm3, 1e6 - 216000 + 8000, 1e-6);

  const auto slices = SlicePlanar(part, {10.0, 30.0, 50.0});
  EXPECT_EQ(slices[0].size(), 1u);
  EXPECT_TRUE(slices[0][0].holes.empty());
  ASSERT_EQ(slices[1].size(), 1u);
  EXPECT_EQ(slices[1][0].holes.size(), 1u);
  EXPECT_NEAR(Area(slices[1]), 10000.0 - 3600.0, 1e-9);
  ASSERT_EQ(slices[2].size(), 2u) << "the island inside the hole is a new outer region";
  EXPECT_EQ(slices[2][0].holes.size(), 1u);
  EXPECT_TRUE(slices[2][1].holes.empty());
  EXPECT_NEAR(Area(slices[2][1]), 400.0, 1e-9);
  for (const auto& slice : slices) ExpectWellFormed(slice, 0.0);
}

TEST(PlanarSlicer, InconsistentFacetOrientationStillGivesOrientedRings) {
  TriangleMesh box = GeneratePart("box", {{"size_mm", {10, 20, 30}}}, "test");
  for (std::size_t f = 0; f < box.facets.size(); f += 3) std::swap(box.facets[f][1], box.facets[f][2]);
  const auto slice = SlicePlanar(box, {15.0}).front();
  ASSERT_EQ(slice.size(), 1u);
  ExpectWellFormed(slice, 15.0);
  EXPECT_NEAR(Area(slice), 200.0, 1e-9);
}

TEST(PlanarSlicer, HeightsComeBackInTheGivenOrder) {
  const TriangleMesh sphere = GeneratePart("sphere", {{"radius_mm", {10}}}, "test");
  const auto sorted = SlicePlanar(sphere, {2.0, 10.0, 18.0});
  const auto shuffled = SlicePlanar(sphere, {18.0, 2.0, 10.0});
  EXPECT_EQ(Area(shuffled[0]), Area(sorted[2]));
  EXPECT_EQ(Area(shuffled[1]), Area(sorted[0]));
  EXPECT_EQ(Area(shuffled[2]), Area(sorted[1]));
  EXPECT_GT(Area(sorted[1]), Area(sorted[0]));
}

TEST(PlanarSlicer, OpenChainsAreReportedOrThrown) {
  TriangleMesh box = GeneratePart("box", {{"size_mm", {10, 10, 10}}}, "test");
  // Drop the side-wall facets cut at z = 5 on one wall: both cut chains of that wall stay open.
  box.facets.erase(box.facets.begin());
  SliceReport report;
  const auto slices = SlicePlanar(box, {5.0, 9.0}, &report);
  EXPECT_EQ(report.open_chains, 2u);
  EXPECT_EQ(report.open_chain_heights_mm, (std::vector<double>{5.0, 9.0}));
  EXPECT_TRUE(slices[0].empty()) << "an open chain is not turned into a region";
  try {
    SlicePlanar(box, {5.0});
    FAIL() << "expected an open-chain error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("slice at z = 5 mm: 1 contour chains do not close"));
  }
}

TEST(PlanarSlicer, NonFiniteHeightIsRefused) {
  const TriangleMesh box = GeneratePart("box", {}, "test");
  try {
    SlicePlanar(box, {1.0, NAN});
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("slice height 1 = nan mm: must be a finite number"));
  }
}

}  // namespace
}  // namespace waam::planner
