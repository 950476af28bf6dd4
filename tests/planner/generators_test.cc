// Tests of the procedural parts: closed and outward-oriented, volumes against analytic values, every bad parameter.
#include "models/core/numbers.h"
#include "planner/mesh/generators.h"

#include <cmath>
#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "planner/mesh/mesh_ops.h"
#include "planner/mesh/stl_io.h"
#include "tests/planner/mesh_test_util.h"
#include "planner/slicing/planar_slicer.h"

namespace waam::planner {
namespace {

using ::testing::HasSubstr;
using testing::ReadStl;

// Area of a regular n-gon inscribed in a circle of radius r.
double PolygonArea(double r, int n) { return 0.5 * n * r * r * std::sin(2 * kPi / n); }

class EveryGenerator : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryGenerator, DefaultsGiveAClosedOutwardMeshOnTheBuildPlate) {
  const TriangleMesh mesh = GeneratePart(GetParam(), {}, "test");
  const MeshReport report = InspectMesh(mesh, 0.0, GetParam());
  EXPECT_TRUE(report.watertight) << report.boundary_edges << " boundary, " << report.non_manifold_edges
                                 << " non-manifold edges";
  EXPECT_EQ(report.misoriented_edges, 0u) << "facets must be consistently oriented";
  EXPECT_EQ(report.degenerate_facets, 0u);
  EXPECT_GT(report.volume_mm3, 0.0) << "normals must point outwards";
  if (GetParam() != "thruster_blades" && GetParam() != "propeller") {  // kept in their axis' frame
    EXPECT_DOUBLE_EQ(report.bbox_min.z(), 0.0) << "the part must sit on z = 0";
    EXPECT_NEAR(report.bbox_min.x() + report.bbox_max.x(), 0.0, 1e-9) << "centred on x = 0";
    EXPECT_NEAR(report.bbox_min.y() + report.bbox_max.y(), 0.0, 1e-9) << "centred on y = 0";
  }
  CheckSliceable(report);
  // Deterministic: a second build is identical.
  const TriangleMesh again = GeneratePart(GetParam(), {}, "test");
  EXPECT_EQ(again.vertices, mesh.vertices);
  EXPECT_EQ(again.facets, mesh.facets);
}

class PrismGenerator : public ::testing::TestWithParam<std::string> {};

TEST_P(PrismGenerator, MidHeightSliceTimesHeightMatchesVolume) {
  const std::string type = GetParam();
  const TriangleMesh mesh = GeneratePart(type, {}, "test");
  Eigen::Vector3d lo, hi;
  BoundingBox(mesh, &lo, &hi);
  const double area = Area(SlicePlanar(mesh, {0.5 * hi.z()}).front());
  EXPECT_NEAR(area * hi.z(), EnclosedVolume(mesh), 1e-9 * EnclosedVolume(mesh))
      << "slice area x height (slicer) must equal the divergence-theorem volume";
}

INSTANTIATE_TEST_SUITE_P(Generators, EveryGenerator, ::testing::ValuesIn(GeneratorTypes()));

std::vector<std::string> PrismTypes() {
  std::vector<std::string> types = GeneratorTypes();
  std::erase_if(types, [](const std::string& t) { return t == "sphere" || t == "torus" || t == "thruster_blades" ||
                                        t == "propeller" || t == "bent_tube" || t == "cup_two_handles"; });
  return types;
}
INSTANTIATE_TEST_SUITE_P(Generators, PrismGenerator, ::testing::ValuesIn(PrismTypes()));

TEST(Generators, ListsTheRequiredTypes) {
  const std::vector<std::string> types = GeneratorTypes();
  for (const char* type : {"box", "plate_with_holes", "l_shape", "t_shape", "ding_a", "ding_b", "ding_c", "ding_d",
                           "cylinder", "rib_web", "sphere", "torus", "bent_tube"}) {
    EXPECT_NE(std::find(types.begin(), types.end(), type), types.end()) << type;
  }
}

TEST(Generators, VolumesMatchAnalyticValues) {
  auto volume = [](const std::string& type, const GeneratorParams& params) {
    return EnclosedVolume(GeneratePart(type, params, "test"));
  };
  EXPECT_NEAR(volume("box", {{"size_mm", {10, 20, 30}}}), 6000.0, 1e-9);
  EXPECT_NEAR(volume("l_shape", {{"size_mm", {100, 80, 10}}, {"leg_mm", {20, 30}}}), (100 * 30 + 20 * 50) * 10.0, 1e-6);
  EXPECT_NEAR(volume("t_shape", {{"size_mm", {100, 80, 10}}, {"flange_mm", {20}}, {"web_mm", {30}}}),
              (100 * 20 + 30 * 60) * 10.0, 1e-6);
  // rib_web: (n px + t)(n py + t) minus the open cells (p - t)^2, times the height.
  EXPECT_NEAR(volume("rib_web", {{"cells", {4, 3}}, {"pitch_mm", {50, 40}}, {"wall_mm", {9}}, {"height_mm", {20}}}),
              ((4 * 50 + 9) * (3 * 40 + 9) - 12 * (50 - 9) * (40 - 9)) * 20.0, 1e-6);
  EXPECT_NEAR(volume("ding_d", {{"height_mm", {10}}}), (2 * 160 * 60 - 60 * 60) * 10.0, 1e-6);
  // Prisms of regular polygons: the polygon area is the exact reference.
  EXPECT_NEAR(volume("cylinder", {{"radius_mm", {20}}, {"height_mm", {50}}, {"segments", {40}}}),
              PolygonArea(20, 40) * 50, 1e-6);
  EXPECT_NEAR(volume("plate_with_holes", {{"size_mm", {100, 60, 5}}, {"hole_diameters_mm", {20, 10}},
                                          {"hole_centers_mm", {-20, 0, 25, 10}}, {"segments", {32}}}),
              (100 * 60 - PolygonArea(10, 32) - PolygonArea(5, 32)) * 5, 1e-6);
  // Curved solids converge to the analytic volume as the tessellation is refined.
  const double sphere = volume("sphere", {{"radius_mm", {40}}, {"segments", {256}}, {"rings", {128}}});
  EXPECT_NEAR(sphere / (4.0 / 3.0 * kPi * 40 * 40 * 40), 1.0, 1e-3);
  const double torus = volume("torus", {{"major_radius_mm", {50}}, {"minor_radius_mm", {15}},
                                        {"major_segments", {256}}, {"minor_segments", {128}}});
  EXPECT_NEAR(torus / (2 * kPi * kPi * 50 * 15 * 15), 1.0, 1e-3);
}

TEST(Generators, CommittedScenarioMeshesAreCurrentAndSliceable) {
  // scenarios/meshes/<type>.stl are `waam generate <type>` outputs with defaults; they must still match.
  const std::filesystem::path dir = std::filesystem::path(WAAM_SOURCE_DIR) / "scenarios" / "meshes";
  int checked = 0;
  for (const std::string& type : GeneratorTypes()) {
    const std::filesystem::path file = dir / (type + ".stl");
    if (!std::filesystem::exists(file)) continue;
    MeshReport report;
    ReadStl(file, 1e-4, &report);
    EXPECT_TRUE(report.binary) << file;
    CheckSliceable(report);
    const double expected = EnclosedVolume(GeneratePart(type, {}, "test"));
    EXPECT_NEAR(report.volume_mm3, expected, 1e-5 * expected) << file << " is stale: regenerate it";
    EXPECT_LT(std::filesystem::file_size(file), 1'000'000u) << file;
    ++checked;
  }
  EXPECT_GE(checked, 10) << "expected the committed meshes in " << dir;
}

std::string GeneratorErrorOf(const std::string& type, const GeneratorParams& params) {
  try {
    GeneratePart(type, params, "s.yaml:7: part.generator");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(GeneratorErrors, NameTheTypeParameterAndRule) {
  EXPECT_THAT(GeneratorErrorOf("blob", {}), HasSubstr("s.yaml:7: part.generator: unknown generator type 'blob' (known: bent_tube, box"));
  EXPECT_THAT(GeneratorErrorOf("box", {{"radius_mm", {1}}}),
              HasSubstr("s.yaml:7: part.generator: unknown parameter 'radius_mm' for generator box (known: size_mm)"));
  EXPECT_THAT(GeneratorErrorOf("box", {{"size_mm", {1, 2}}}), HasSubstr("box.size_mm = [1, 2]: needs 3 values"));
  EXPECT_THAT(GeneratorErrorOf("cylinder", {{"radius_mm", {-1}}}), HasSubstr("cylinder.radius_mm = [-1]: each value must be in"));
  EXPECT_THAT(GeneratorErrorOf("cylinder", {{"segments", {10.5}}}), HasSubstr("cylinder.segments = [10.5]: must be whole"));
  EXPECT_THAT(GeneratorErrorOf("cylinder", {{"height_mm", {NAN}}}), HasSubstr("cylinder.height_mm"));
  EXPECT_THAT(GeneratorErrorOf("torus", {{"minor_radius_mm", {60}}}), HasSubstr("minor_radius_mm = 60: must be smaller"));
  EXPECT_THAT(GeneratorErrorOf("l_shape", {{"leg_mm", {200, 10}}}), HasSubstr("l_shape.leg_mm = [200, 10]: must be smaller"));
  EXPECT_THAT(GeneratorErrorOf("t_shape", {{"web_mm", {500}}}), HasSubstr("t_shape flange_mm = 25 and web_mm = 500"));
  EXPECT_THAT(GeneratorErrorOf("rib_web", {{"wall_mm", {70}}}), HasSubstr("rib_web.wall_mm = 70: must be smaller than the rib"));
  EXPECT_THAT(GeneratorErrorOf("plate_with_holes", {{"hole_diameters_mm", {10}}}),
              HasSubstr("hole_centers_mm has 6 values: needs 2 (x, y) per hole"));
  EXPECT_THAT(GeneratorErrorOf("plate_with_holes", {{"hole_diameters_mm", {10}}, {"hole_centers_mm", {78, 0}}}),
              HasSubstr("hole 1 (diameter 10 mm at 78, 0 mm from the plate centre) must lie inside"));
  EXPECT_THAT(GeneratorErrorOf("plate_with_holes", {{"hole_diameters_mm", {20, 20}}, {"hole_centers_mm", {0, 0, 10, 0}}}),
              HasSubstr("holes 1 and 2 are -10 mm apart"));
}

}  // namespace
}  // namespace waam::planner
