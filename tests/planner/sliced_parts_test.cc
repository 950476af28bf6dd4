// The continuous pattern on the sliced scenario meshes: one pass per layer and the uncovered fraction per part.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "planner/mesh/stl_io.h"
#include "tests/planner/mesh_test_util.h"
#include "planner/path/layer_pattern.h"
#include "planner/slicing/planar_slicer.h"
#include "pattern_checks.h"

namespace waam::planner {
namespace {

constexpr double kSlicedW = 6.0;  // bead width, mm

struct Part {
  std::string mesh;     // scenarios/meshes/<mesh>.stl
  double max_uncovered;  // fraction of the slice area, on every layer tested
};

// Slices six layers 1.5 mm apart from the bottom of each mesh (as `waam plan` does for the continuous scenarios),
// plans them with layer_index 0..5 and prints the measured figures (run with --gtest_filter=SlicedParts.*).
// Bounds: the corners and tips a round bead centred w/2 inside the wall cannot reach, the cusps between raster ends,
// and around round bores the gap between the bore's ring and the pieces cut from around its octagon (ding_b, ding_c).
TEST(SlicedParts, ContinuousOnePassAndCovered) {
  const std::vector<Part> parts{{"cylinder", 0.015},  {"ding_a", 0.015}, {"ding_b", 0.03},
                                {"ding_c", 0.03},     {"ding_d", 0.01},  {"plate_with_holes", 0.012},
                                {"sphere", 0.025}};
  std::printf("| mesh | passes (max) | elements per layer (mean) | uncovered mean %% | uncovered worst %% |\n");
  std::printf("|---|---|---|---|---|\n");
  for (const Part& part : parts) {
    MeshReport report;
    const TriangleMesh mesh =
        testing::ReadStl(std::string(WAAM_SOURCE_DIR) + "/scenarios/meshes/" + part.mesh + ".stl", 1e-4, &report);  // as PlanScenario
    double z_min = mesh.vertices.front().z();
    for (const Eigen::Vector3d& v : mesh.vertices) z_min = std::min(z_min, v.z());
    std::vector<double> heights;
    for (int i = 0; i < 6; ++i) heights.push_back(z_min + 0.75 + 1.5 * i);
    const auto slices = SlicePlanar(mesh, heights);
    int max_passes = 0, elements = 0;
    double mean = 0.0, worst = 0.0;
    for (int i = 0; i < 6; ++i) {
      PatternOptions options;
      options.bead_width_mm = kSlicedW;
      options.layer_index = i;
      const std::vector<Move2D> moves = PlanLayerPattern(slices[i], options);
      double uncovered = 0.0, area = 0.0;
      for (const PolygonWithHoles& region : slices[i]) {
        uncovered += testing::UncoveredFraction(region, moves, kSlicedW) * Area(region);
        area += Area(region);
      }
      const int passes = testing::CountPasses(moves);
      EXPECT_EQ(passes, static_cast<int>(slices[i].size())) << part.mesh << " layer " << i << ": one pass per region";
      EXPECT_LT(uncovered / area, part.max_uncovered) << part.mesh << " layer " << i;
      max_passes = std::max(max_passes, passes);
      elements += testing::CountWeldMoves(moves);
      mean += uncovered / area / 6.0;
      worst = std::max(worst, uncovered / area);
    }
    std::printf("| %s | %d | %.1f | %.2f | %.2f |\n", part.mesh.c_str(), max_passes, elements / 6.0, 100.0 * mean,
                100.0 * worst);
  }
}

}  // namespace
}  // namespace waam::planner
