// Tests of the cup with two handles and its centroid-shift overhang decomposition (dissertation 003 sec. 5.4).
#include "models/core/numbers.h"
#include "planner/slicing/centroid_decomposition.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "planner/mesh/cup_generator.h"
#include "planner/mesh/generators.h"
#include "planner/mesh/mesh_ops.h"
#include "planner/multidir_planner.h"
#include "planner/plan_scenario.h"
#include "tests/planner/test_scenarios.h"

namespace waam::planner {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(CupGeneratorTest, ClosedManifoldAndTheAnalyticVolume) {
  const CupParams p;
  const TriangleMesh mesh = GeneratePart("cup_two_handles", {}, "test");
  const MeshReport report = InspectMesh(mesh, 0.0, "cup_two_handles");
  EXPECT_TRUE(report.watertight) << report.boundary_edges << " boundary edges";
  EXPECT_EQ(report.non_manifold_edges, 0u);
  EXPECT_EQ(report.misoriented_edges, 0u);
  // Chords of the 96-gon and the 24-gon tube sections make the mesh a little smaller than the analytic part.
  const double analytic = CupTwoHandlesVolume(p);
  EXPECT_NEAR(report.volume_mm3 / analytic, 1.0, 0.005) << "mesh " << report.volume_mm3 << " mm^3, analytic "
                                                        << analytic << " mm^3";
  Eigen::Vector3d lo, hi;
  BoundingBox(mesh, &lo, &hi);
  const double reach = p.radius_mm + p.handle_radius_mm + p.handle_tube_mm;
  EXPECT_NEAR(hi.x(), reach, 0.01) << "the +x handle's outermost point";
  EXPECT_NEAR(lo.x(), -reach, 0.01) << "the -x handle's outermost point";
  EXPECT_NEAR(lo.z(), 0.0, 1e-9);
  EXPECT_NEAR(hi.z(), p.height_mm, 1e-9);
}

TEST(CupGeneratorTest, HandlesOutsideTheCupAreRefused) {
  try {
    GeneratePart("cup_two_handles", {{"handle_z_mm", {20.0}}}, "s.yaml:3: part.generator");
    FAIL() << "expected an InputError for handles reaching below the cup";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("s.yaml:3: part.generator: cup_two_handles.handle_z_mm = 20"));
  }
  try {
    GeneratePart("cup_two_handles", {{"handle_mm", {5.0, 6.0}}}, "test");
    FAIL() << "expected an InputError for a tube wider than the handle";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("tube radius must be < the handle radius"));
  }
}

TEST(CentroidDecompositionTest, TheCupSplitsIntoBodyAndTwoHandlesBuiltOutwards) {
  const CupParams p;
  const TriangleMesh mesh = GeneratePart("cup_two_handles", {}, "test");
  CentroidSplitOptions options;
  options.step_mm = 1.1;
  const CentroidDecomposition d = DecomposeByCentroidShift(mesh, options, "test: slicing");
  ASSERT_EQ(d.features.size(), 2u) << "one feature per handle";
  ASSERT_EQ(d.sub_volumes.size(), 3u);
  EXPECT_EQ(d.sub_volumes[0].name, "body");
  EXPECT_EQ(d.sub_volumes[0].direction, (std::array<double, 3>{0, 0, 1}));
  EXPECT_EQ(d.sub_volumes[0].keep.size(), 2u) << "the body keeps the cup side of both split planes";
  double side_sum = 0.0;
  for (const OverhangFeature& f : d.features) {
    // Split plane x = +-R (the wall the handle leaves), built along the outward normal.
    const double side = f.split_normal.x() > 0 ? 1.0 : -1.0;
    side_sum += side;
    EXPECT_GT(std::abs(f.split_normal.x()), 0.999) << f.name << " normal " << f.split_normal.transpose();
    EXPECT_NEAR(f.split_offset_mm, p.radius_mm, 0.6) << f.name;
    // Centroid of a half-torus: 2 r_h / pi from its diameter (Pappus), at the handle's centre height.
    EXPECT_NEAR(side * f.centroid_mm.x(), p.radius_mm + 2.0 * p.handle_radius_mm / kPi, 0.5) << f.name;
    EXPECT_NEAR(f.centroid_mm.z(), p.handle_z_mm, 0.6) << f.name;
    EXPECT_GT(f.axis.dot(f.split_normal), 0.999) << "the centroidal axis leaves the wall along the normal";
    EXPECT_GT(f.max_gamma_deg, options.overhang_deg);
    const double half_torus = kPi * kPi * p.handle_tube_mm * p.handle_tube_mm * p.handle_radius_mm;
    EXPECT_NEAR(f.volume_mm3 / half_torus, 1.0, 0.03) << f.name;
  }
  EXPECT_EQ(side_sum, 0.0) << "one handle on each side";
}

TEST(CentroidDecompositionTest, PartsWithoutOverhangsAreNotSplit) {
  CentroidSplitOptions options;
  options.step_mm = 1.5;
  for (const std::string type : {"box", "cylinder", "sphere"}) {
    const CentroidDecomposition d = DecomposeByCentroidShift(GeneratePart(type, {}, "test"), options, "test");
    EXPECT_TRUE(d.features.empty()) << type << ": " << d.features.size() << " features";
    ASSERT_EQ(d.sub_volumes.size(), 1u) << type;
    EXPECT_TRUE(d.sub_volumes[0].keep.empty()) << type;
  }
  // The lower half of a sphere overhangs everywhere, but evenly: its centroid chain stays on the axis, so the
  // candidates go back to the body (the centroid-shift test, eq. 5.26).
  const CentroidDecomposition sphere = DecomposeByCentroidShift(GeneratePart("sphere", {}, "test"), options, "test");
  EXPECT_GT(sphere.candidates_merged, 0) << "the sphere's lower half should give overhang candidates";
}

TEST(CentroidDecompositionTest, HandlesLeaningLessThanTheLimitStayWithTheBody) {
  // The handles' centroid chains lean about 66 deg (eq. 5.26); with a 70 deg limit (a layer may step out 3 mm) the
  // handles still start candidates, but the centroid-shift test keeps them with the body.
  CentroidSplitOptions options;
  options.step_mm = 1.1;
  options.overhang_deg = 70.0;
  const CentroidDecomposition d = DecomposeByCentroidShift(GeneratePart("cup_two_handles", {}, "test"), options, "test");
  EXPECT_TRUE(d.features.empty()) << d.features.size() << " features";
  EXPECT_GE(d.candidates_merged, 2) << "at least one candidate per handle";
  ASSERT_EQ(d.sub_volumes.size(), 1u);
}

TEST(CentroidDecompositionTest, BadOptionsAreNamed) {
  const TriangleMesh mesh = GeneratePart("box", {}, "test");
  CentroidSplitOptions options;
  options.overhang_deg = 90.0;
  try {
    DecomposeByCentroidShift(mesh, options, "s.yaml: slicing");
    FAIL() << "expected an InputError for overhang_deg = 90";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("s.yaml: slicing.overhang_deg = 90: must be in (0, 90) deg"));
  }
}

PlannerSections CupScenario() {
  PlannerSections s;
  s.name = "cup";
  s.part.generator = PartGenerator::kCupTwoHandles;
  s.part.where = "test: part.generator";
  s.slicing.type = SlicingType::kMultiDirectional;
  s.slicing.split = SplitMethod::kCentroidShift;
  s.slicing.layer_height_mm = 2.5;  // divides the 5 mm bottom: the slices count it exactly
  s.path.pattern = Pattern::kContour;
  s.path.bead_width_mm = 4.0;
  return s;
}

TEST(CentroidDecompositionTest, PlannedSubVolumesAddUpToThePart) {
  const PlanResult result = PlanScenario(testing::WithFiles(CupScenario()), nullptr);
  ASSERT_EQ(result.sub_volumes.size(), 3u);
  double sum = 0.0;
  for (const SubVolumeReport& sub : result.sub_volumes) {
    sum += sub.volume_mm3;
    ASSERT_GT(sub.layers, 0) << sub.name;
    for (int i = sub.first_layer; i < sub.first_layer + sub.layers; ++i) {
      for (const PathPoint& point : result.plan.layers[i].points) {
        EXPECT_LT((point.tool_dir_P - sub.direction).norm(), 1e-12) << sub.name;
        if (sub.name != "body") {
          EXPECT_GT(point.p_P.dot(sub.direction), 37.0) << sub.name << " beyond the wall";
        }
      }
    }
    if (sub.name != "body") {
      EXPECT_GT(sub.centroid_lean_deg, 15.0) << sub.name;
      EXPECT_EQ(sub.keep.size(), 1u) << sub.name;
    }
  }
  EXPECT_NEAR(sum / EnclosedVolume(result.mesh), 1.0, 0.02) << "the sub-volumes share the part between them";
  for (const SubVolumeReport& sub : result.sub_volumes) {
    EXPECT_EQ(sub.unwelded_mm3, 0.0) << sub.name << ": the contour pattern should find a path in every slice";
  }
  EXPECT_LT(result.sub_volumes[0].support_mm3, 0.01 * result.sub_volumes[0].volume_mm3)
      << "the cup body built upwards stands on its bottom";
}

}  // namespace
}  // namespace waam::planner
