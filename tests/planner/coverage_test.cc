// UncoveredArea: the slice minus the planned beads, in the slice plane.
#include "planner/path/coverage.h"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "planner/geometry/clipper_adapter.h"
#include "test_shapes.h"

namespace waam::planner {
namespace {

// A 20 x 10 mm slice and one weld move 10 mm long along its middle, bead 10 mm wide: the bead (a 10 x 10 mm square
// with two half discs of radius 5 mm) leaves 200 - (100 + 25 pi) mm^2 of it, plus what the disc's chords (within
// kArcToleranceMm of the circle) miss: at most its perimeter times that tolerance.
LayerPath OneBead(const Eigen::Matrix<double, 3, 2>& axes, const Eigen::Vector3d& origin) {
  LayerPath layer;
  layer.slice = {{testing::Rect(0, 0, 20, 10), {}}};
  layer.slice_axes_P = axes;
  layer.slice_origin_P = origin;
  for (const auto& [x, weld] : {std::pair{5.0, false}, {15.0, true}}) {
    PathPoint p;
    p.p_P = origin + axes * Eigen::Vector2d(x, 5.0);
    p.bead_width_mm = 10.0;
    p.weld = weld;
    layer.points.push_back(p);
  }
  return layer;
}

TEST(Coverage, OneBeadInARectangle) {
  const double expected = 200.0 - (100.0 + 25.0 * std::numbers::pi);
  const double chords = 2.0 * std::numbers::pi * 5.0 * internal::kArcToleranceMm;
  const LayerPath flat = OneBead(Eigen::Matrix<double, 3, 2>::Identity(), Eigen::Vector3d(0, 0, 3));
  EXPECT_NEAR(UncoveredArea(flat), expected + 0.5 * chords, 0.5 * chords);
  // The same layer built sideways (slice plane x = 50 mm, axes y and z): the same area, measured in its plane.
  Eigen::Matrix<double, 3, 2> sideways;
  sideways.col(0) = Eigen::Vector3d::UnitY();
  sideways.col(1) = Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(UncoveredArea(OneBead(sideways, Eigen::Vector3d(50, 0, 0))), UncoveredArea(flat), 1e-6);
  LayerPath travel_only = flat;
  travel_only.points.back().weld = false;
  EXPECT_NEAR(UncoveredArea(travel_only), 200.0, 1e-6) << "a travel move lays no bead";
  LayerPath cone = flat;
  cone.slice_in_plane = false;
  EXPECT_TRUE(std::isnan(UncoveredArea(cone))) << "a development-plane slice is not measured";
}

// Concentric contour rings d2 = w/2 apart filling an annulus 200 mm across, like the contour pattern on a torus slice, with
// three rings missing: measured column by column the uncovered area is the one a single Clipper difference
// of all the beads gives.
TEST(Coverage, ColumnsGiveTheAreaOfOneDifference) {
  const double w = 2.0;
  LayerPath layer;
  layer.slice = {{testing::Circle(0, 0, 100, 720), {testing::Circle(0, 0, 60, 480, true)}}};
  std::vector<internal::Polyline> rings;
  for (double r = 100 - 0.5 * w; r > 60 + 0.5 * w; r -= 0.5 * w) {
    if (std::abs(r - 80.0) < 1.6) continue;  // three missing rings leave a band 2 mm wide bare
    internal::Polyline ring;
    for (int k = 0; k <= 180; ++k) {
      const double a = 2.0 * std::numbers::pi * k / 180;
      ring.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    for (std::size_t k = 0; k < ring.size(); ++k) {
      PathPoint p;
      p.p_P = Eigen::Vector3d(ring[k].x(), ring[k].y(), 2.0);
      p.bead_width_mm = w;
      p.weld = k > 0;
      layer.points.push_back(p);
    }
    rings.push_back(std::move(ring));
  }
  const double direct = Area(internal::Difference(layer.slice, internal::BufferPolylines(rings, 0.5 * w)));
  const double measured = UncoveredArea(layer);
  EXPECT_GT(direct, 2.0 * std::numbers::pi * 80.0 * 2.0 * 0.95) << "the band between r = 79 and 81 mm is bare";
  EXPECT_NEAR(measured, direct, 1e-6 * Area(layer.slice));
}

}  // namespace
}  // namespace waam::planner
