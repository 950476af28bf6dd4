// The exported surface mesh is closed, faces outward and encloses the deposited volume.
#include "tests/twin/twin_settings.h"
#include "twin/scanner/surface_mesh.h"

#include <gtest/gtest.h>

#include "models/core/error.h"
#include "planner/mesh/mesh_ops.h"
#include "tests/twin/test_paths.h"
#include "twin/deposition/bead_deposition.h"

namespace waam::twin {
namespace {

TEST(SurfaceMesh, BlockIsClosedWithTheRightVolume) {
  VoxelGrid grid(0.5, 100000);
  for (int k = 0; k < 12; ++k)
    for (int j = -5; j < 15; ++j)
      for (int i = 0; i < 20; ++i) grid.Set(VoxelIndex(i, j, k), VoxelData{});
  const planner::TriangleMesh mesh = ExtractSurface(grid);
  EXPECT_EQ(OpenEdges(mesh), 0u) << "the surface must be closed";
  // Iso-surface through the edge midpoints: faces are flat on the block's faces, edges and corners are chamfered.
  const double volume = planner::EnclosedVolume(mesh);
  EXPECT_GT(volume, 0.0) << "facets must face outward";
  EXPECT_NEAR(volume, grid.OccupiedVolume(), 0.05 * grid.OccupiedVolume());
}

TEST(SurfaceMesh, DepositedBeadsGiveAClosedSurface) {
  planner::Plan plan;
  planner::LayerPath layer;
  testing::AddPass(&layer, {{0, 0}, {30, 0}, {30, 20}}, 2.0, 6.0, 2.0, 8.0);
  plan.layers.push_back(layer);
  const Depositor d = DepositPlan(plan, twin::TestSimulationSettings(), 100.0, nullptr);
  const planner::TriangleMesh mesh = ExtractSurface(d.grid());
  EXPECT_EQ(OpenEdges(mesh), 0u);
  EXPECT_NEAR(planner::EnclosedVolume(mesh), d.grid().OccupiedVolume(), 0.1 * d.grid().OccupiedVolume());
}

TEST(SurfaceMesh, CoarsenKeepsAlignedBlocksAndCountsFaces) {
  VoxelGrid grid(0.5, 100000);
  for (int k = 0; k < 4; ++k)
    for (int j = -4; j < 4; ++j)
      for (int i = 0; i < 8; ++i) grid.Set(VoxelIndex(i, j, k), VoxelData{});
  EXPECT_EQ(ExposedFaces(grid), 8u * 8u + 4u * 8u * 4u) << "top and four sides; the bottom is on the substrate";
  const VoxelGrid coarse = Coarsen(grid, 2);
  EXPECT_DOUBLE_EQ(coarse.voxel_mm(), 1.0);
  EXPECT_EQ(coarse.occupied(), 4u * 4u * 2u);
  EXPECT_DOUBLE_EQ(coarse.OccupiedVolume(), grid.OccupiedVolume());
  EXPECT_THROW(Coarsen(grid, 0), InputError);
}

}  // namespace
}  // namespace waam::twin
