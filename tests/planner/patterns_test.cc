// Tests of the layer patterns: pass counts, coverage, staying inside, start alternation and bad options.
#include "planner/path/layer_pattern.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "planner/geometry/clipper_adapter.h"
#include "planner/geometry/convex_decomposition.h"
#include "planner/path/convex_fill.h"
#include "planner/path/pattern_common.h"
#include "pattern_checks.h"
#include "test_shapes.h"

namespace waam::planner {
namespace {

using ::testing::HasSubstr;

constexpr double kW = 6.0;  // bead width, mm

std::vector<Move2D> Plan(const PolygonWithHoles& region, const std::string& pattern, int layer = 0) {
  PatternOptions options;
  options.pattern = ParseEnum<Pattern>(pattern).value();
  options.bead_width_mm = kW;
  options.layer_index = layer;
  return PlanLayerPattern({region}, options);
}

using testing::CountPasses;
using testing::CountWeldMoves;
using testing::WeldLengthOutside;

double UncoveredFraction(const PolygonWithHoles& region, const std::vector<Move2D>& moves) {
  return testing::UncoveredFraction(region, moves, kW);
}

std::vector<std::pair<std::string, PolygonWithHoles>> AllShapes() {
  std::vector<std::pair<std::string, PolygonWithHoles>> shapes = testing::DingLikeShapes();
  shapes.emplace_back("L", testing::LShape());
  shapes.emplace_back("T", testing::TShape());
  shapes.emplace_back("U", testing::UShape());
  shapes.emplace_back("plate with holes", testing::PlateWithHoles());
  return shapes;
}

TEST(ContinuousPattern, OnePassPerLayer) {
  for (const auto& [name, region] : AllShapes()) {
    for (int layer = 0; layer < 3; ++layer) {
      const std::vector<Move2D> moves = Plan(region, "continuous", layer);
      ASSERT_FALSE(moves.empty()) << name;
      EXPECT_FALSE(moves.front().weld) << name << ": a layer starts with the torch off";
      EXPECT_EQ(CountPasses(moves), 1) << name << " layer " << layer << ": Ding's path is one pass per layer";
    }
  }
}

// Bound: beads of w = 6 mm along the path leave < 3 % of each ~100 mm part uncovered (the cusps between raster
// ends and where piece contours meet at a split line).
TEST(ContinuousPattern, CoversTheRegion) {
  for (const auto& [name, region] : AllShapes()) {
    const double uncovered = UncoveredFraction(region, Plan(region, "continuous"));
    EXPECT_LT(uncovered, 0.03) << name << ": uncovered fraction " << uncovered;
  }
}

// Random star-shaped parts (~160 mm across, seeded), a third with a bore: one pass, and < 4 % uncovered (their
// acute tips, which no round bead centred w/2 inside the wall reaches, make up most of it).
TEST(ContinuousPattern, RandomStarsOnePassAndCovered) {
  std::mt19937_64 rng(99);
  for (int k = 0; k < 15; ++k) {
    PolygonWithHoles star = testing::RandomStar(rng, 8 + k % 12, 80.0);
    if (k % 3 == 0) star.holes.push_back(testing::Circle(0, 0, 10, k % 2 ? 6 : 20, true));
    const std::vector<Move2D> moves = Plan(star, "continuous", k);
    EXPECT_EQ(CountPasses(moves), 1) << "star " << k;
    EXPECT_LT(UncoveredFraction(star, moves), 0.04) << "star " << k;
  }
}

// A 160 x 100 mm plate with three bores, like scenarios/planar_demo.yaml. Cuts that end at the plate's corners at
// small angles leave wedges a bead centred w/2 inside cannot reach (~90 mm2 each at 15 degrees); with cuts at
// >= 45 degrees to the wall the layer is < 1.2 % uncovered on every layer.
TEST(ContinuousPattern, PlateWithBoresCovered) {
  PolygonWithHoles plate{testing::Rect(-80, -50, 80, 50), {}};
  plate.holes.push_back(testing::Circle(-35, 0, 18, 96, true));
  plate.holes.push_back(testing::Circle(35, 25, 13, 96, true));
  plate.holes.push_back(testing::Circle(35, -25, 13, 96, true));
  for (int layer = 0; layer < 6; ++layer) {
    const std::vector<Move2D> moves = Plan(plate, "continuous", layer);
    EXPECT_EQ(CountPasses(moves), 1) << "layer " << layer;
    EXPECT_LT(UncoveredFraction(plate, moves), 0.012) << "layer " << layer;
  }
}

TEST(ContinuousPattern, WeldsStayInsideTheRegion) {
  for (const auto& [name, region] : AllShapes()) {
    const auto inside = internal::Offset({region}, 0.01);
    EXPECT_LT(WeldLengthOutside(Plan(region, "continuous"), inside), 1e-3) << name;
  }
}

TEST(HybridPattern, NeedsMorePassesThanContinuous) {
  for (const auto& [name, region] : testing::DingLikeShapes()) {
    const int hybrid = CountPasses(Plan(region, "hybrid"));
    EXPECT_GT(hybrid, CountPasses(Plan(region, "continuous"))) << name;
    EXPECT_GE(hybrid, 1 + static_cast<int>(region.holes.size()) + 1)
        << name << ": one pass per contour ring plus at least one zigzag pass";
    EXPECT_LT(UncoveredFraction(region, Plan(region, "hybrid")), 0.03) << name;
  }
}

TEST(ContourAndZigzag, StayHalfABeadInside) {
  for (const auto& [name, region] : AllShapes()) {
    const auto inset = internal::Offset({region}, -(0.5 * kW - 0.02));
    for (const std::string pattern : {"contour", "zigzag"}) {
      const std::vector<Move2D> moves = Plan(region, pattern);
      EXPECT_GT(CountWeldMoves(moves), 0) << name << " " << pattern;
      EXPECT_LT(WeldLengthOutside(moves, inset), 1e-3) << name << " " << pattern << ": beads must not cross the wall";
    }
  }
}

TEST(ContourPattern, RingsFillTheRegion) {
  for (const auto& [name, region] : AllShapes()) {
    EXPECT_LT(UncoveredFraction(region, Plan(region, "contour")), 0.03) << name;
  }
}

TEST(ZigzagPattern, FixedAngleRunsAlongIt) {
  PatternOptions options;
  options.pattern = Pattern::kZigzag;
  options.zigzag_auto = false;
  options.zigzag_angle_rad = 0.0;
  const std::vector<Move2D> moves = PlanLayerPattern({{testing::Rect(0, 0, 100, 60), {}}}, options);
  // A rectangle filled along x: rasters at y from 3 to 57 mm, at most l = 4.428 mm apart -> 14 lines, one pass.
  EXPECT_EQ(CountPasses(moves), 1);
  int along_x = 0;
  for (std::size_t k = 1; k < moves.size(); ++k) {
    if (std::abs(moves[k].p.y() - moves[k - 1].p.y()) < 1e-9 && moves[k].weld) ++along_x;
  }
  EXPECT_EQ(along_x, 14);
}

// Hybrid and continuous on a 100 x 60 mm plate with x rasters (the continuous pattern finds that direction itself):
// the contour centre line is w/2 = 3 mm in, the lowest raster d1 above it (0.47 w proposed, 0.738 w existing) and
// neighbouring rasters at most l = 0.738 w apart.
TEST(PatternSpacing, FollowsTheOverlapModel) {
  for (const auto& [pattern, model] : std::vector<std::pair<std::string, std::string>>{
           {"hybrid", "proposed"}, {"hybrid", "existing"}, {"continuous", "proposed"}, {"continuous", "existing"}}) {
    PatternOptions options;
    options.pattern = ParseEnum<Pattern>(pattern).value();
    options.overlap_model = ParseEnum<OverlapModel>(model).value();
    options.zigzag_auto = pattern == "continuous";
    const OverlapSpacing s = OverlapSpacingFor(options.overlap_model, options.bead_width_mm);
    const std::vector<Move2D> moves = PlanLayerPattern({{testing::Rect(0, 0, 100, 60), {}}}, options);
    std::vector<double> raster_y;
    for (std::size_t k = 1; k < moves.size(); ++k) {
      const bool horizontal = std::abs(moves[k].p.y() - moves[k - 1].p.y()) < 1e-9;
      const bool interior = moves[k].p.y() > 3.5 && moves[k].p.y() < 56.5;
      if (moves[k].weld && horizontal && interior) raster_y.push_back(moves[k].p.y());
    }
    SCOPED_TRACE(pattern);
    ASSERT_FALSE(raster_y.empty()) << model;
    std::sort(raster_y.begin(), raster_y.end());
    raster_y.erase(std::unique(raster_y.begin(), raster_y.end()), raster_y.end());
    EXPECT_NEAR(raster_y.front() - s.boundary_offset_mm, s.contour_to_zigzag_mm, 0.01) << model;
    EXPECT_NEAR(60.0 - s.boundary_offset_mm - raster_y.back(), s.contour_to_zigzag_mm, 0.01) << model;
    for (std::size_t k = 1; k < raster_y.size(); ++k) {
      EXPECT_LE(raster_y[k] - raster_y[k - 1], s.zigzag_mm + 1e-9) << model;
      EXPECT_GT(raster_y[k] - raster_y[k - 1], 0.8 * s.zigzag_mm) << model << ": no raster needlessly close";
    }
  }
}

TEST(ZigzagPattern, LinkAcrossAHoleIsTravel) {
  // Rasters on both sides of a hole cannot be joined by a weld across it: the zigzag needs > 1 pass.
  PolygonWithHoles plate{testing::Rect(0, 0, 100, 100), {testing::Rect(30, 30, 70, 70, true)}};
  const std::vector<Move2D> moves = Plan(plate, "zigzag");
  EXPECT_GT(CountPasses(moves), 1);
  EXPECT_LT(WeldLengthOutside(moves, internal::Offset({plate}, -(0.5 * kW - 0.02))), 1e-3);
}

TEST(StartPoints, AlternateLayerToLayer) {
  for (const std::string pattern : {"contour", "continuous", "hybrid", "zigzag"}) {
    const auto first = Plan(testing::LShape(), pattern, 0);
    const auto second = Plan(testing::LShape(), pattern, 1);
    EXPECT_GT((first.front().p - second.front().p).norm(), kW)
        << pattern << ": consecutive layers should not start at the same place";
  }
}

TEST(StartPoints, SameInputSamePath) {
  const auto a = Plan(testing::PlateWithHoles(), "continuous", 4);
  const auto b = Plan(testing::PlateWithHoles(), "continuous", 4);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].p, b[k].p);
    EXPECT_EQ(a[k].weld, b[k].weld);
  }
}

TEST(PlanLayerPattern, SeparateRegionsAreSeparatePasses) {
  PatternOptions options;
  const std::vector<Move2D> moves =
      PlanLayerPattern({{testing::Rect(0, 0, 50, 50), {}}, {testing::Rect(80, 0, 130, 50), {}}}, options);
  EXPECT_EQ(CountPasses(moves), 2);
}

TEST(SimplifyMoves, MergesStraightRunsOnly) {
  const double tol = internal::kStraightPathToleranceMm;
  // Travel to (0,0); weld along x through points 0.5 tol off the line; a corner; then arc off and weld again.
  std::vector<Move2D> moves{{{0, 0}, false}, {{10, 0.5 * tol}, true}, {{20, -0.5 * tol}, true}, {{30, 0}, true},
                            {{30, 10}, true}, {{30, 20}, true}, {{40, 20}, false}, {{50, 20}, true}};
  const std::vector<Move2D> out = internal::SimplifyMoves(moves, tol);
  ASSERT_EQ(out.size(), 5u) << "expected start, one move along x, one along y, travel, weld";
  EXPECT_EQ(out[1].p, Eigen::Vector2d(30, 0));
  EXPECT_EQ(out[2].p, Eigen::Vector2d(30, 20));
  EXPECT_FALSE(out[3].weld) << "arc-off travel is kept";
  EXPECT_TRUE(out[4].weld);
  // A point further off the line than the tolerance is a corner and stays.
  const std::vector<Move2D> bent{{{0, 0}, false}, {{10, 2 * tol}, true}, {{20, 0}, true}};
  EXPECT_EQ(internal::SimplifyMoves(bent, tol).size(), 3u);
  // A move that turns back is never merged, however small the offset.
  const std::vector<Move2D> back{{{0, 0}, false}, {{10, 0}, true}, {{5, 0}, true}};
  EXPECT_EQ(internal::SimplifyMoves(back, tol).size(), 3u);
}

// A circle of radius 60 mm tessellated into 400 sides (0.94 mm edges): the outer contour ring must not keep 400
// elements. A chord of sagitta <= 0.05 mm spans <= 2 acos(1 - 0.05 / 57) = 4.8 degrees of the ring's 57 mm centre
// line, so the ring needs >= 75 chords; merging only points within the tolerance keeps it under twice that.
TEST(SimplifyMoves, FinelyTessellatedRingBecomesFewElements) {
  const std::vector<Move2D> moves = Plan({testing::Circle(0, 0, 60, 400), {}}, "contour");
  int ring_elements = 0;
  for (std::size_t k = 1; k < moves.size() && moves[k].weld; ++k) ++ring_elements;  // the outer ring comes first
  EXPECT_LT(ring_elements, 150) << "elements in the outer contour ring";
  EXPECT_GE(ring_elements, 75) << "the ring cannot be followed within 0.05 mm with fewer chords";
  for (int k = 1; k <= ring_elements; ++k) {
    // Each move is a chord of the 57 mm ring: its mid-point lies at most the tolerances inside the ring.
    const double mid_radius = (0.5 * (moves[k].p + moves[k - 1].p)).norm();
    EXPECT_GT(mid_radius, 57.0 - internal::kStraightPathToleranceMm - internal::kArcToleranceMm) << "move " << k;
  }
}

// The continuous path on a 2000-sided circle: the contour chain alone has ~1000 vertices and the turnarounds on
// the other chain hundreds more; merged, the whole loop is the ~27 rasters, their turnarounds and < 75 chords.
TEST(SimplifyMoves, ContinuousPathOnAFineCircle) {
  const PolygonWithHoles disc{testing::Circle(0, 0, 60, 2000), {}};
  const std::vector<Move2D> moves = Plan(disc, "continuous");
  EXPECT_EQ(CountPasses(moves), 1);
  EXPECT_LT(CountWeldMoves(moves), 200) << "weld moves (path elements) in the layer";
  EXPECT_LT(UncoveredFraction(disc, moves), 0.01);
}

// Trapezoids with one wall at 30 degrees to the rasters, on the right or (mirrored) on the left: turnarounds on
// that wall lie 2 l apart along it and leave wedges, so the contour must be laid on that wall. The continuous path
// covers as well as the better of the two ways round of Ding's per-piece loop, and clearly better than the worse.
TEST(ContinuousPattern, ContourGoesOnTheObliqueWall) {
  const double run = 40 * std::sqrt(3.0);
  for (const Ring& trapezoid : {testing::Poly({{0, 0}, {120, 0}, {120 - run, 40}, {0, 40}}),
                                testing::Poly({{0, 0}, {120, 0}, {120, 40}, {run, 40}})}) {
    const PolygonWithHoles region{trapezoid, {}};
    const OverlapSpacing spacing = OverlapSpacingFor(OverlapModel::kProposed, kW);
    auto loop_moves = [&](double angle) {
      std::vector<Move2D> moves;
      internal::AppendLoop(internal::ConvexPieceLoop(trapezoid, angle, spacing), Eigen::Vector2d::Zero(), false,
                           &moves);
      return moves;
    };
    const double one_way = UncoveredFraction(region, loop_moves(0.0));
    const double other_way = UncoveredFraction(region, loop_moves(std::numbers::pi));
    const double planned = UncoveredFraction(region, Plan(region, "continuous"));
    EXPECT_LE(planned, std::min(one_way, other_way) + 1e-4) << one_way << " / " << other_way;
    EXPECT_GT(std::max(one_way, other_way), planned + 0.002) << "the two ways round should differ on this part";
  }
}

// The loop needs an even number of rasters. Spreading a fixed count evenly over every piece (Ding) would put rasters
// a third of l apart in pieces a little taller than one step, nearly tripling the metal there on every layer; the
// count is the even one whose pitch is nearest l, so the pitch stays between 0.55 l and 1.8 l once a piece holds more
// than two rasters.
TEST(ContinuousPattern, RasterPitchStaysNearTheStepOver) {
  const OverlapSpacing spacing = OverlapSpacingFor(OverlapModel::kProposed, kW);
  const double l = spacing.zigzag_mm;
  for (double height = 16.0; height <= 40.0; height += 0.37) {
    const Ring piece = testing::Poly({{0, 0}, {60, 0}, {60, height}, {0, height}});
    const Ring loop = internal::ConvexPieceLoop(piece, 0.0, spacing);
    std::vector<double> levels;  // heights of the long horizontal runs: top contour, rasters, bottom contour
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Eigen::Vector2d& a = loop[i];
      const Eigen::Vector2d& b = loop[(i + 1) % loop.size()];
      if (std::abs(a.y() - b.y()) < 1e-6 && std::abs(a.x() - b.x()) > 30.0) levels.push_back(a.y());
    }
    std::sort(levels.begin(), levels.end());
    ASSERT_GE(levels.size(), 4u) << "height " << height;
    for (std::size_t k = 2; k + 1 < levels.size(); ++k) {  // between rasters, not to the contour
      const double pitch = levels[k] - levels[k - 1];
      EXPECT_GT(pitch, 0.55 * l) << "height " << height << " mm: rasters " << pitch << " mm apart, l = " << l;
      EXPECT_LT(pitch, 1.8 * l) << "height " << height << " mm: rasters " << pitch << " mm apart, l = " << l;
    }
  }
}

// A side a piece shares with its neighbour is not a wall: its bead goes l/2 inside (the neighbour's l/2 beyond), the
// rasters l from it; the walls keep w/2 and d1. Square 40 x 40, rasters along x, the top side shared.
TEST(ContinuousPattern, SharedSideKeepsTheZigzagSpacing) {
  const OverlapSpacing spacing = OverlapSpacingFor(OverlapModel::kProposed, kW);
  const double l = spacing.zigzag_mm;
  const Ring square = testing::Poly({{0, 0}, {40, 0}, {40, 40}, {0, 40}});
  const std::vector<bool> top_shared{false, false, true, false};  // edge 2: (40,40) -> (0,40)
  for (const std::vector<bool>& shared : {std::vector<bool>{}, top_shared}) {
    const Ring loop = internal::ConvexPieceLoop(square, 0.0, spacing, shared);
    ASSERT_GE(loop.size(), 4u);
    double y_max = -1.0, y_min = 1e9, x_min = 1e9, x_max = -1.0;
    std::vector<double> levels;  // heights of the long runs along x
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Eigen::Vector2d& a = loop[i];
      const Eigen::Vector2d& b = loop[(i + 1) % loop.size()];
      y_max = std::max(y_max, a.y()), y_min = std::min(y_min, a.y());
      x_min = std::min(x_min, a.x()), x_max = std::max(x_max, a.x());
      if (std::abs(a.y() - b.y()) < 1e-6 && std::abs(a.x() - b.x()) > 15.0) levels.push_back(a.y());
    }
    std::sort(levels.begin(), levels.end());
    levels.erase(std::unique(levels.begin(), levels.end(), [](double a, double b) { return std::abs(a - b) < 1e-6; }),
                 levels.end());
    ASSERT_GE(levels.size(), 3u);
    const bool top_is_shared = !shared.empty();
    EXPECT_NEAR(40.0 - y_max, top_is_shared ? 0.5 * l : 0.5 * kW, 1e-3) << "top bead inset";
    EXPECT_NEAR(y_min, 0.5 * kW, 1e-3) << "a wall keeps its bead w/2 inside";
    EXPECT_NEAR(x_min, 0.5 * kW, 1e-3);
    EXPECT_NEAR(40.0 - x_max, 0.5 * kW, 1e-3);
    const double top_gap = levels.back() - levels[levels.size() - 2];
    if (top_is_shared) {
      EXPECT_GE(top_gap, l - 1e-3) << "first raster l (not d1) below the bead on a shared side";
    } else {
      EXPECT_GE(top_gap, spacing.contour_to_zigzag_mm - 1e-3);
    }
  }
}

// On odd layers each piece's loop runs the other way round (contour and turnarounds change sides), so the piles
// and gaps at the turnarounds do not stack up layer on layer. A 60 x 40 rectangle: rasters along x, the turnarounds
// on one end, the contour on the other.
TEST(ContinuousPattern, TurnaroundsChangeSidesOnOddLayers) {
  const PolygonWithHoles region{testing::Rect(0, 0, 60, 40), {}};
  auto corners_on_left = [&](int layer) {
    const std::vector<Move2D> moves = Plan(region, "continuous", layer);
    // Points on the contour's centre line at either end (w/2 from the wall): there the rasters turn, while on the
    // contour's end only its two corners lie on it (the rasters stop d1 short).
    int left = 0, right = 0;
    for (const Move2D& m : moves) {
      if (m.p.x() < 0.5 * kW + 0.1) ++left;
      if (m.p.x() > 60.0 - 0.5 * kW - 0.1) ++right;
    }
    EXPECT_GT(std::max(left, right), 2 * std::min(left, right)) << "layer " << layer << ": " << left << " / " << right;
    return left > right;
  };
  const bool even = corners_on_left(0);
  EXPECT_NE(corners_on_left(1), even) << "layer 1 should have its turnarounds on the other end";
  EXPECT_EQ(corners_on_left(2), even) << "layer 2 should be laid like layer 0";
  for (int layer : {0, 1}) {
    EXPECT_LT(UncoveredFraction(region, Plan(region, "continuous", layer)), 0.01) << "layer " << layer;
  }
}

// A curved wall two beads wide: Ding's decomposition of the tessellated band cuts at every facet of its inner arc
// (2 deg apart, each a notch) into slivers narrower than a bead, and the pattern used to find no path at all. With
// the shallow notches cut off first it is one pass covering all but the cusps; the chords on the inner arc put the
// beads at most w/10 beyond it.
TEST(ContinuousPattern, CurvedWallIsOnePassAndCovered) {
  const PolygonWithHoles band = testing::ArcBand(60.0, 60.0 + 2.0 * kW, 70.0, 35);
  for (int layer = 0; layer < 2; ++layer) {
    const std::vector<Move2D> moves = Plan(band, "continuous", layer);
    EXPECT_EQ(CountPasses(moves), 1) << "layer " << layer;
    EXPECT_LT(UncoveredFraction(band, moves), 0.05) << "layer " << layer;
    // Weld moves keep (w/2 - w/10) inside the band's outline: the path may lie w/10 beyond the true inner arc.
    const std::vector<PolygonWithHoles> inner = internal::Offset({band}, -(0.5 * kW - 0.1 * kW - 0.05));
    EXPECT_LT(WeldLengthOutside(moves, inner), 1e-3) << "layer " << layer;
  }
}

// The same wall with contours: one ring two beads wide fills it. The next offset reaches the medial axis and leaves
// crumbs along it, which must not become passes of their own (an arc start and stop on the spot).
TEST(ContourPattern, WallTwoBeadsWideIsOneRing) {
  const PolygonWithHoles band = testing::ArcBand(60.0, 60.0 + 2.0 * kW, 70.0, 35);
  const std::vector<Move2D> moves = Plan(band, "contour");
  EXPECT_EQ(CountPasses(moves), 1);
  EXPECT_LT(UncoveredFraction(band, moves), 0.02);
  const PolygonWithHoles island{testing::Rect(0, 0, 1.2 * kW, 1.2 * kW), {}};
  EXPECT_EQ(CountPasses(Plan(island, "contour")), 1) << "an island about a bead wide still gets its (short) ring";
}

TEST(PlanLayerPattern, HasWeldOrNoRoom) {
  const std::vector<PolygonWithHoles> square{{testing::Rect(0, 0, 30, 30), {}}};
  const std::vector<PolygonWithHoles> sliver{{testing::Rect(0, 0, 30, 0.8 * kW), {}}};
  EXPECT_FALSE(HasWeldOrNoRoom(square, {}, kW)) << "room for beads and no weld move: a layer would go missing";
  EXPECT_FALSE(HasWeldOrNoRoom(square, {{{5, 5}, false}, {{25, 5}, false}}, kW)) << "travel only";
  EXPECT_TRUE(HasWeldOrNoRoom(square, {{{5, 5}, false}, {{25, 5}, true}}, kW));
  EXPECT_TRUE(HasWeldOrNoRoom(sliver, {}, kW)) << "narrower than a bead: no path is the right answer";
}

TEST(PlanLayerPattern, EmptySliceGivesNoMoves) { EXPECT_TRUE(PlanLayerPattern({}, PatternOptions{}).empty()); }

TEST(PlanLayerPattern, RejectsBadOptions) {
  auto expect_error = [](PatternOptions options, const std::string& text) {
    try {
      PlanLayerPattern({testing::LShape()}, options);
      FAIL() << "expected InputError mentioning " << text;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(text));
    }
  };
  PatternOptions unknown;
  unknown.pattern = Pattern::kSpiral;
  expect_error(unknown, "path pattern 'spiral'");
  PatternOptions width;
  width.bead_width_mm = -2.0;
  expect_error(width, "bead_width_mm = -2");
  PatternOptions layer;
  layer.layer_index = -1;
  expect_error(layer, "layer_index = -1");
}

}  // namespace
}  // namespace waam::planner
