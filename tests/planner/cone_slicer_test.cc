// Tests of cone/cylinder slicing, flattening and planning (Dai et al. 2020 sec. 2 and 5).
#include "models/core/numbers.h"
#include "planner/slicing/cone_slicer.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/bead/csw_model.h"
#include "models/core/error.h"
#include "models/fit/model_file.h"
#include "planner/cone_planner.h"
#include "planner/plan_scenario.h"
#include "tests/planner/test_scenarios.h"
#include "planner/mesh/generators.h"

namespace waam::planner {
namespace {
using ::testing::HasSubstr;
constexpr double kInf = std::numeric_limits<double>::infinity();

ConeSurface Cone(double R, double H) {
  ConeSurface s;
  s.R = R;
  s.H = H;
  return s;
}

// A 100 x 60 x 40 mm box centred on the z axis, z in [0, 40].
TriangleMesh Box() { return GeneratePart("box", {{"size_mm", {100.0, 60.0, 40.0}}}, "test"); }

TEST(ConeSurfaceTest, FlattenThenMapBackReturnsThePoint) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> theta(-kPi, kPi), z(-50.0, 150.0), alpha(0.0, 2 * kPi);
  for (const ConeSurface& s : {Cone(60, 200), Cone(40, -300), Cone(25, kInf)}) {
    for (int i = 0; i < 200; ++i) {
      const double t = theta(rng), h = z(rng), a = alpha(rng);
      const double r = s.RadiusAt(h);
      const Eigen::Vector3d p(r * std::cos(t), r * std::sin(t), h);
      ASSERT_NEAR(s.Residual(p), 0.0, 1e-9 * r * r);
      const Eigen::Vector3d back = s.Unflatten(s.Flatten(p, a), a);
      EXPECT_LT((back - p).norm(), 1e-9) << "R " << s.R << " H " << s.H << " theta " << t << " z " << h;
    }
  }
}

TEST(ConeSurfaceTest, FlatteningKeepsArcLengths) {
  // A wavy curve on the surface, finely sampled: its length in space equals its length on the plane.
  for (const ConeSurface& s : {Cone(60, 200), Cone(25, kInf)}) {
    double space = 0.0, plane = 0.0;
    Eigen::Vector3d last_p;
    Eigen::Vector2d last_q;
    const int n = 20000;
    for (int i = 0; i <= n; ++i) {
      const double u = static_cast<double>(i) / n;
      const double t = -2.0 + 3.5 * u + 0.3 * std::sin(9 * u);
      const double h = 20.0 + 60.0 * u + 10.0 * std::cos(7 * u);
      const double r = s.RadiusAt(h);
      const Eigen::Vector3d p(r * std::cos(t), r * std::sin(t), h);
      const Eigen::Vector2d q = s.Flatten(p, 0.3);
      if (i > 0) {
        space += (p - last_p).norm();
        plane += (q - last_q).norm();
      }
      last_p = p;
      last_q = q;
    }
    EXPECT_NEAR(plane / space, 1.0, 1e-6) << "R " << s.R << " H " << s.H << ": lengths " << space << " vs " << plane;
  }
}

TEST(ConeSurfaceTest, OffsetIsEquidistantAsInTheThrusterExample) {
  // Dai sec. 5: R_i = 60 + sqrt(109)/10 d i, H_i = 200 + sqrt(109)/3 d i.
  const ConeSurface s = Cone(60, 200).Offset(2.5 * 3);
  EXPECT_NEAR(s.R, 60 + std::sqrt(109.0) / 10 * 7.5, 1e-9);
  EXPECT_NEAR(s.H, 200 + std::sqrt(109.0) / 3 * 7.5, 1e-9);
  const Eigen::Vector3d p(60 * std::cos(0.4) * 0.75, 60 * std::sin(0.4) * 0.75, 50.0);  // on the first cone
  EXPECT_NEAR(s.NormalOffset(p + 7.5 * Cone(60, 200).Normal(p)), 0.0, 1e-9);
}

TEST(ConeSlicerTest, ContoursLieOnTheSurface) {
  const TriangleMesh box = Box();
  for (const ConeSurface& s : {Cone(40, 200), Cone(40, kInf)}) {
    ConeSliceStats stats;
    const std::vector<Contour3d> contours = SliceWithCone(box, s, &stats);
    ASSERT_EQ(contours.size(), 2u) << "R = 40 meets the 60 mm wide box in two patches, H " << s.H;
    EXPECT_EQ(stats.open_chains, 0u);
    for (const Contour3d& c : contours) {
      for (const Eigen::Vector3d& p : c) EXPECT_LT(std::abs(s.Residual(p)), 1e-9 * s.R * s.R) << p.transpose();
    }
  }
}

TEST(ConeSlicerTest, FlattenedCylinderPatchHasTheAnalyticArea) {
  const ConeSurface s = Cone(40, kInf);
  const FlatLayer flat = FlattenLayer(SliceWithCone(Box(), s, nullptr), s, 11 * kPi / 180);
  ASSERT_TRUE(flat.ok) << flat.message;
  EXPECT_NE(flat.alpha, 0.0) << "the patch round theta = pi crosses the cutting line; it must be turned";
  // Two patches |40 sin theta| <= 30, 40 mm high: area 2 * R * 2 asin(0.75) * 40.
  // (Clipper's 0.1 um grid along the ~400 mm of outline allows a few hundredths of a mm^2.)
  EXPECT_NEAR(Area(flat.regions), 2 * 40 * 2 * std::asin(0.75) * 40, 0.05);
}

TEST(ConeSlicerTest, AFacetCanBeCutIntoThreeSegments) {
  // One flat triangle round a cylinder of radius 10 whose edges pass 7.5 mm from the axis: 6 points, 3 segments.
  TriangleMesh tri;
  for (int k = 0; k < 3; ++k) tri.vertices.emplace_back(15 * std::cos(2 * kPi * k / 3), 15 * std::sin(2 * kPi * k / 3), 0);
  tri.facets.push_back({0, 1, 2});
  ConeSliceStats stats;
  SliceWithCone(tri, Cone(10, kInf), &stats);
  EXPECT_EQ(stats.edge_points, 6u);
  EXPECT_EQ(stats.facets_with_segments[3], 1u);
}

TEST(ConeSlicerTest, AContourRoundTheAxisCannotBeFlattened) {
  const TriangleMesh cylinder = GeneratePart("cylinder", {{"radius_mm", {50.0}}}, "test");
  const ConeSurface s = Cone(30, kInf);
  const FlatLayer flat = FlattenLayer(SliceWithCone(cylinder, s, nullptr), s, 11 * kPi / 180);
  EXPECT_FALSE(flat.ok);
  EXPECT_THAT(flat.message, HasSubstr("winds round the surface axis"));
}

PlannerSections BladeScenario() {
  PlannerSections s;
  s.name = "blades";
  s.part.generator = PartGenerator::kThrusterBlades;
  s.part.params = {{"blades", {3.0}}, {"span_mm", {12.0}}, {"chord_mm", {30.0}}, {"thickness_mm", {14.0, 10.0}}};
  s.part.where = "test: part.generator";
  s.slicing.type = SlicingType::kCone;
  s.slicing.cone_R_mm = 60;
  s.slicing.cone_H_mm = 200;
  s.slicing.layer_height_mm = 2.5;
  s.path.pattern = Pattern::kContour;
  s.path.bead_width_mm = 9.0;
  s.process.bead_model = BeadModel::kCsw;
  s.process.wire_diameter_mm = 1.2;
  s.process.wire_feed_mm_min = 6500;
  return s;
}

TEST(ConePlannerTest, PathLiesOnTheLayerTopsWithTheToolAlongTheNormal) {
  PlannerSections scenario = BladeScenario();
  scenario.path.retract_mm = 0.0;  // the planner's own travel, on the surface (retracts: retract_test.cc)
  const PlanResult result = PlanScenario(testing::WithFiles(scenario), nullptr);
  ASSERT_EQ(result.plan.layers.size(), 5u) << "12 mm span at 2.5 mm layers";
  const ConeSurface base = Cone(60, 200);
  for (const LayerPath& layer : result.plan.layers) {
    ASSERT_FALSE(layer.points.empty());
    for (const PathPoint& p : layer.points) {
      EXPECT_NEAR(base.NormalOffset(p.p_P), 2.5 * (layer.index + 1), 1e-6) << "layer " << layer.index;
      EXPECT_LT((p.tool_dir_P - base.Normal(p.p_P)).norm(), 1e-9);
      // CSW speeds stay in the model's feasible window (Dai Table 1: 300-900 mm/min).
      EXPECT_GE(p.speed_mm_s * 60, 300 - 1e-9);
      EXPECT_LE(p.speed_mm_s * 60, 900 + 1e-9);
    }
  }
  EXPECT_EQ(result.stats.passes_per_layer.front(), 3u) << "one contour pass per blade";
}

TEST(ConePlannerTest, CswSpeedsUpOnTighterCurves) {
  const PlanResult result = PlanScenario(testing::WithFiles(BladeScenario()), nullptr);
  double lo = 1e9, hi = 0;
  for (const LayerPath& layer : result.plan.layers) {
    for (const PathPoint& p : layer.points) {
      if (!p.weld) continue;
      lo = std::min(lo, p.speed_mm_s * 60);
      hi = std::max(hi, p.speed_mm_s * 60);
    }
  }
  // The nominal speed is the straight-line inverse of the shipped CSW fit (models/data/csw.json, Dai Table 1);
  // the ends of the blade sections curve tighter and need a faster travel for the same width.
  const models::CswModel csw = models::CswModel::Load(models::DefaultModelPath("csw"));
  EXPECT_NEAR(result.travel_speed_mm_min, csw.SpeedForWidth(9.0, kInf).speed_mm_per_min, 1e-9);
  EXPECT_GE(lo, result.travel_speed_mm_min - 1e-9) << "no bend needs a slower speed than a straight line";
  EXPECT_GT(hi, lo + 50) << "speed range " << lo << " - " << hi;
}

TEST(ConePlannerTest, CswIsNotUsedBeyondItsData) {
  // The blade sections' rounded ends turn on radii below one bead width: corners, where p/r (p = 52.7 mm^2) would
  // plan beads twice as wide and a tenth as high. Corners keep the straight-line speed and width; curves below the
  // smallest radius of Dai's Table 1 (30 mm) are planned as 30 mm (CswModel::ApplicableRadius).
  const PlannerSections scenario = BladeScenario();
  const PlanResult result = PlanScenario(testing::WithFiles(scenario), nullptr);
  const models::CswModel csw = models::CswModel::Load(models::DefaultModelPath("csw"));
  const double widest = csw.Width(csw.feasible().min_mm_per_min, scenario.process.csw_min_radius_mm);
  std::size_t weld_points = 0;
  for (const LayerPath& layer : result.plan.layers) {
    for (const PathPoint& p : layer.points) {
      if (!p.weld) continue;
      ++weld_points;
      EXPECT_LE(p.bead_width_mm, widest + 1e-9) << "layer " << layer.index << " at " << p.p_P.transpose();
      EXPECT_NEAR(p.bead_width_mm, 9.0, 0.01) << "the speed window reaches 9 mm on every radius the model covers";
    }
  }
  EXPECT_GT(weld_points, 100u);
}

TEST(ConePlannerTest, PathStaysOnTheSurfaceAcrossAWideDevelopment) {
  // R = 80, H = 70: the development is a sector of 270 deg, wider than pi; weld and travel moves between the nine
  // blades must stay on the surface, consecutive points a step apart (no jump across the cutting line).
  PlannerSections s = BladeScenario();
  s.part.params = {{"blades", {9.0}}, {"R_mm", {80.0}}, {"H_mm", {70.0}}, {"root_z_mm", {20.0}}, {"span_mm", {6.0}},
                   {"chord_mm", {30.0}}, {"thickness_mm", {12.0, 10.0}}, {"pitch_deg", {20.0, 30.0}}};
  s.slicing.cone_R_mm = 80;
  s.slicing.cone_H_mm = 70;
  s.path.retract_mm = 0.0;  // the planner's own travel, on the surface (retracts: retract_test.cc)
  const PlanResult result = PlanScenario(testing::WithFiles(s), nullptr);
  ASSERT_FALSE(result.plan.layers.empty());
  for (const LayerPath& layer : result.plan.layers) {
    EXPECT_EQ(result.stats.passes_per_layer[layer.index], 9u) << "one contour pass per blade";
    for (std::size_t j = 1; j < layer.points.size(); ++j) {
      EXPECT_LT((layer.points[j].p_P - layer.points[j - 1].p_P).norm(), 3.0)
          << "layer " << layer.index << " point " << j << (layer.points[j].weld ? " (weld)" : " (travel)");
    }
  }
}

TEST(ConePlannerTest, PartPastTheApexIsRefused) {
  PlannerSections s = BladeScenario();
  s.slicing.cone_H_mm = 70;
  EXPECT_THROW(
      {
        try {
          PlanScenario(testing::WithFiles(s), nullptr);
        } catch (const InputError& e) {
          EXPECT_THAT(e.what(), HasSubstr("past the cone apex"));
          throw;
        }
      },
      InputError);
}

TEST(ConePlannerTest, PartInsideTheFirstSurfaceIsRefused) {
  PlannerSections s = BladeScenario();
  s.slicing.cone_R_mm = 200;  // every blade lies inside this cone
  try {
    PlanScenario(testing::WithFiles(s), nullptr);
    FAIL() << "expected an InputError for a part inside the first surface";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("lies inside the first surface"));
  }
}

TEST(ConePlannerTest, ALayerRoundTheAxisIsRefusedWithItsIndex) {
  // A tube round the cylinder's axis: every layer is a full ring that no cutting line can miss.
  PlannerSections s = BladeScenario();
  s.part.generator = PartGenerator::kCylinder;
  s.part.params = {{"radius_mm", {50.0}}, {"height_mm", {20.0}}};
  s.slicing.type = SlicingType::kCylinder;
  s.slicing.cone_R_mm = 40;
  try {
    PlanScenario(testing::WithFiles(s), nullptr);
    FAIL() << "expected an InputError for a contour winding round the axis";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("layer 0"));
    EXPECT_THAT(e.what(), HasSubstr("winds round the surface axis"));
  }
}

TEST(ConePlannerTest, NoLayerIsDroppedSilentlyWhateverThePattern) {
  // Every pattern either welds all five layers of the blades or stops naming the layer it could not fill: a slice
  // wider than a bead that ends without a weld path must never vanish from the plan, the cell check and the twin.
  for (const char* pattern : {"contour", "zigzag", "hybrid", "continuous"}) {
    PlannerSections s = BladeScenario();
    s.path.pattern = ParseEnum<Pattern>(pattern).value();
    try {
      const PlanResult result = PlanScenario(testing::WithFiles(s), nullptr);
      EXPECT_EQ(result.plan.layers.size(), 5u) << pattern << ": 12 mm span at 2.5 mm layers";
      for (const LayerPath& layer : result.plan.layers) {
        EXPECT_TRUE(std::any_of(layer.points.begin(), layer.points.end(), [](const PathPoint& p) { return p.weld; }))
            << pattern << ": layer " << layer.index << " has no weld move";
      }
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr("found no weld path")) << pattern;
      EXPECT_THAT(e.what(), HasSubstr("layer ")) << pattern;
    }
  }
}

}  // namespace
}  // namespace waam::planner
