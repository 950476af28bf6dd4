// Eulerian rib-web path (003 sec. 4.3): one closed weld pass per layer, every stretch of path welded once.
#include "planner/path/eulerian_pattern.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "planner/path/layer_pattern.h"
#include "planner/planar_planner.h"
#include "planner/scenario/scenario.h"
#include "tests/planner/pattern_checks.h"
#include "tests/planner/test_shapes.h"

namespace waam::planner {
namespace {

using testing::CountPasses;
using testing::Rect;

// A rib-web grid slice: outer wall and ribs `wall` thick around nx x ny open cells of pitch px, py (as the
// rib_web generator builds it).
PolygonWithHoles Grid(int nx, int ny, double px, double py, double wall) {
  PolygonWithHoles region{Rect(-wall / 2, -wall / 2, nx * px + wall / 2, ny * py + wall / 2), {}};
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      region.holes.push_back(
          Rect(i * px + wall / 2, j * py + wall / 2, (i + 1) * px - wall / 2, (j + 1) * py - wall / 2, true));
    }
  }
  return region;
}

std::map<std::string, PolygonWithHoles> RibWebShapes() {
  std::map<std::string, PolygonWithHoles> shapes;
  shapes["grid 1x1"] = Grid(1, 1, 60, 60, 9);
  shapes["grid 2x2 (Fig. 47)"] = Grid(2, 2, 60, 60, 9);
  shapes["grid 3x2"] = Grid(3, 2, 50, 70, 9);
  shapes["grid 1x4"] = Grid(1, 4, 80, 40, 9);
  shapes["grid 3x3"] = Grid(3, 3, 45, 45, 10);
  // Non-rectangular cells: a triangular frame with a rib from its apex (two triangular cells, 9 mm walls).
  const Ring left = testing::Poly({{0, 0}, {60, 0}, {60, 100}});
  const Ring right = testing::Poly({{60, 0}, {120, 0}, {60, 100}});
  const auto outer = internal::Offset({{testing::Poly({{0, 0}, {120, 0}, {60, 100}}), {}}}, 4.5);
  auto cells = internal::Offset({{left, {}}}, -4.5);
  for (const auto& c : internal::Offset({{right, {}}}, -4.5)) cells.push_back(c);
  const auto frame = internal::Difference(outer, cells);
  if (frame.size() == 1) shapes["triangle with rib"] = frame[0];
  return shapes;
}

// Undirected segment key on a 1 um grid.
std::tuple<long, long, long, long> Key(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  auto q = [](double v) { return std::lround(v * 1000.0); };
  std::tuple<long, long, long, long> ka{q(a.x()), q(a.y()), q(b.x()), q(b.y())};
  std::tuple<long, long, long, long> kb{q(b.x()), q(b.y()), q(a.x()), q(a.y())};
  return std::min(ka, kb);
}

TEST(Eulerian, OneClosedPassPerLayerEachEdgeOnce) {
  ASSERT_EQ(RibWebShapes().size(), 6u) << "expected five grids and the triangular frame";
  for (const auto& [name, region] : RibWebShapes()) {
    PatternOptions options;
    options.pattern = Pattern::kEulerian;
    options.bead_width_mm = 6.0;
    options.seed = 7;
    const OverlapSpacing spacing = OverlapSpacingFor(OverlapModel::kProposed, 6.0);
    const std::vector<Ring> curves = internal::SharpOffsetCurves(region, spacing);
    double curve_length = 0.0;
    for (const Ring& c : curves) curve_length += Perimeter(c);
    ASSERT_GE(curves.size(), 2u) << name << ": expected an outer curve and one per cell";
    for (int layer = 0; layer < 4; ++layer) {
      options.layer_index = layer;
      const std::vector<Move2D> moves = PlanLayerPattern({region}, options);
      ASSERT_FALSE(moves.empty()) << name;
      EXPECT_EQ(CountPasses(moves), 1) << name << " layer " << layer << ": expected one weld pass";
      EXPECT_FALSE(moves.front().weld);
      for (std::size_t k = 1; k < moves.size(); ++k) EXPECT_TRUE(moves[k].weld) << name << ": no arc-off move";
      EXPECT_LT((moves.back().p - moves.front().p).norm(), 1e-6) << name << ": the pass must end where it starts";
      // Each edge once: no segment welded twice, and the welded length equals the offset curves' length (each
      // connector pair replaces exactly the two gaps it cuts out, so nothing is doubled or left out).
      std::set<std::tuple<long, long, long, long>> seen;
      double weld = 0.0;
      for (std::size_t k = 1; k < moves.size(); ++k) {
        EXPECT_TRUE(seen.insert(Key(moves[k - 1].p, moves[k].p)).second)
            << name << ": segment " << k << " welded twice";
        weld += (moves[k].p - moves[k - 1].p).norm();
      }
      EXPECT_NEAR(weld, curve_length, 1e-3 * curve_length) << name << ": welded length vs offset curves";
      EXPECT_LT(testing::WeldLengthOutside(moves, {region}), 0.01) << name << ": welds stay on the part";
    }
    const internal::JoinedCurves joined = internal::JoinOffsetCurves(curves, {region}, 6.0, 3);
    EXPECT_EQ(joined.loops.size(), 1u) << name;
    EXPECT_EQ(joined.connectors, 2 * (curves.size() - 1)) << name << ": 2 (n - 1) connector lines (sec. 4.3)";
  }
}

TEST(Eulerian, SeededConnectorsRepeatAndMove) {
  const PolygonWithHoles region = Grid(2, 2, 60, 60, 9);
  PatternOptions options;
  options.pattern = Pattern::kEulerian;
  options.seed = 11;
  const std::vector<Move2D> a = PlanLayerPattern({region}, options);
  const std::vector<Move2D> b = PlanLayerPattern({region}, options);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k].p, b[k].p) << "same seed, same path";
  options.layer_index = 1;
  const std::vector<Move2D> c = PlanLayerPattern({region}, options);
  bool differs = c.size() != a.size();
  for (std::size_t k = 0; !differs && k < a.size(); ++k) differs = (a[k].p - c[k].p).norm() > 1e-6;
  EXPECT_TRUE(differs) << "the next layer draws its connectors elsewhere";
}

TEST(Eulerian, ContoursNeedOnePassPerCurve) {
  PatternOptions options;
  options.pattern = Pattern::kContour;
  // 5.3 mm beads on 9 mm walls, 3.7 mm apart (sec. 4.6.5): the existing model's 0.738 w spacing.
  options.bead_width_mm = 5.3;
  options.overlap_model = OverlapModel::kExisting;
  EXPECT_EQ(CountPasses(PlanLayerPattern({Grid(2, 2, 60, 60, 9)}, options)), 5)
      << "the 2x2 grid of Fig. 47: outer wall and four cells, five contours (003 Table 13)";
}

TEST(Eulerian, RegionThatIsNotARibWebIsRefused) {
  // A plate with a small round hole: the hole's curve has no straight stretch to put connectors on.
  PolygonWithHoles plate{Rect(0, 0, 80, 80), {testing::Circle(40, 40, 3, 12, true)}};
  PatternOptions options;
  options.pattern = Pattern::kEulerian;
  options.layer_index = 3;
  try {
    PlanLayerPattern({plate}, options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("path.pattern eulerian: layer 3:"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("closed passes, not 1: every wall must hold two beads"));
  }
}

}  // namespace
}  // namespace waam::planner
