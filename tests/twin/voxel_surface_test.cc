// The greedy-meshed part surface: closed and manifold as the STL reader sees it, the occupied volume, few facets.
#include "tests/twin/twin_settings.h"
#include "models/core/files.h"
#include "twin/scanner/voxel_surface.h"

#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "planner/mesh/mesh_ops.h"
#include "analysis/stl_file.h"
#include "planner/mesh/stl_io.h"
#include "tests/twin/test_paths.h"
#include "twin/deposition/bead_deposition.h"
#include "twin/scanner/surface_mesh.h"

namespace waam::twin {
namespace {

// The report the slicer's STL reader gives for `mesh` written to and read back from a binary STL.
planner::MeshReport ReadBack(const planner::TriangleMesh& mesh, const std::string& name) {
  const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / (name + ".stl");
  analysis::WriteStlBinary(mesh, path, name);
  planner::MeshReport report;
  planner::ParseStl(ReadFile(path), path, 1e-4, &report);
  return report;
}

void ExpectClosedManifold(const planner::TriangleMesh& mesh, const std::string& name) {
  const planner::MeshReport report = ReadBack(mesh, name);
  EXPECT_EQ(report.degenerate_facets, 0u) << name;
  EXPECT_EQ(report.boundary_edges, 0u) << name << ": no cracks";
  EXPECT_EQ(report.non_manifold_edges, 0u) << name;
  EXPECT_EQ(report.misoriented_edges, 0u) << name;
  EXPECT_TRUE(report.watertight) << name;
  EXPECT_EQ(OpenEdges(mesh), 0u) << name;
}

TEST(VoxelSurface, BlockIsTwelveTrianglesWithItsExactVolume) {
  VoxelGrid grid(0.5, 100000);
  for (int k = 0; k < 12; ++k)
    for (int j = -5; j < 15; ++j)
      for (int i = 0; i < 20; ++i) grid.Set(VoxelIndex(i, j, k), VoxelData{});
  const planner::TriangleMesh mesh = ExtractVoxelSurface(grid);
  EXPECT_EQ(mesh.facets.size(), 12u) << "six faces, two triangles each";
  ExpectClosedManifold(mesh, "block");
  EXPECT_NEAR(planner::EnclosedVolume(mesh), grid.OccupiedVolume(), 1e-9) << "faces outward around exactly the voxels";
}

// A step on the top face puts corners of the upper block on the edges of the lower block's rectangles: T-junctions
// that must be split, or the surface cracks.
TEST(VoxelSurface, StepsAreSplitWithoutCracks) {
  VoxelGrid grid(1.0, 100000);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 10; ++i) {
        if (k < 3 || (i >= 3 && i < 7 && j >= 2) || (k == 5 && i == 9)) grid.Set(VoxelIndex(i, j, k), VoxelData{});
      }
  const planner::TriangleMesh mesh = ExtractVoxelSurface(grid);
  ExpectClosedManifold(mesh, "steps");
  EXPECT_NEAR(planner::EnclosedVolume(mesh), grid.OccupiedVolume(), 1e-9);
}

// Voxels touching along an edge only (a chessboard) would give edges of four facets: filled until manifold.
TEST(VoxelSurface, EdgeContactsAreMadeManifold) {
  VoxelGrid grid(1.0, 100000);
  std::mt19937 random(7);
  std::bernoulli_distribution metal(0.45);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        if ((i + j + k) % 2 == 0 || metal(random)) grid.Set(VoxelIndex(i, j, k), VoxelData{});
      }
  const planner::TriangleMesh mesh = ExtractVoxelSurface(grid);
  ExpectClosedManifold(mesh, "chessboard");
  EXPECT_GE(planner::EnclosedVolume(mesh), grid.OccupiedVolume() - 1e-9) << "filling only adds voxels";
}

// Deposited beads: closed, the voxels' volume within the few filled voxels, and far fewer facets than the
// marching-tetrahedra surface of the same grid.
TEST(VoxelSurface, DepositedBeadsGiveAClosedSurfaceWithFewFacets) {
  planner::Plan plan;
  for (int l = 0; l < 3; ++l) {
    planner::LayerPath layer;
    layer.index = l;
    testing::AddPass(&layer, {{0, 0}, {40, 0}, {40, 30}, {0, 30}}, 2.0 + 1.8 * l, 6.0, 2.0, 8.0);
    plan.layers.push_back(layer);
  }
  const Depositor d = DepositPlan(plan, twin::TestSimulationSettings(), 100.0, nullptr);
  const planner::TriangleMesh mesh = ExtractVoxelSurface(d.grid());
  ExpectClosedManifold(mesh, "beads");
  EXPECT_NEAR(planner::EnclosedVolume(mesh), d.grid().OccupiedVolume(), 0.01 * d.grid().OccupiedVolume());
  const std::size_t tetra_facets = ExtractSurface(d.grid()).facets.size();
  EXPECT_LT(mesh.facets.size(), tetra_facets / 4) << "greedy mesh " << mesh.facets.size() << " facets, marching "
                                                  << "tetrahedra " << tetra_facets;
}

}  // namespace
}  // namespace waam::twin
