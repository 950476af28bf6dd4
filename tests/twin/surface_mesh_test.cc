// The exported surface mesh is closed, faces outward and encloses the deposited volume.
#include "tests/twin/twin_settings.h"
#include "twin/scanner/surface_mesh.h"

#include <array>
#include <map>
#include <random>

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

// The block-wise bit counts against the voxel-by-voxel definitions on a random grid across many blocks, negative
// coordinates included: exposed faces (six neighbours each, the substrate solid) and the majority rule of Coarsen
// with the data of the first fine voxel (in ForEach order) of each coarse voxel, for factors that divide the block
// and factors that do not.
TEST(SurfaceMesh, BlockwiseCountsMatchTheVoxelByVoxelDefinitions) {
  VoxelGrid grid(0.5, 1000000);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> xy(-13, 18), z(0, 20);
  for (int n = 0; n < 9000; ++n) {
    grid.Set(VoxelIndex(xy(rng), xy(rng), z(rng)), VoxelData{static_cast<std::uint32_t>(n), 0.0f});
  }
  std::size_t faces = 0;
  const VoxelIndex dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  grid.ForEach([&](const VoxelIndex& v, const VoxelData&) {
    for (const VoxelIndex& d : dirs) faces += grid.Solid(v + d) ? 0 : 1;
  });
  EXPECT_EQ(ExposedFaces(grid), faces);
  for (const int factor : {2, 3, 4, 5}) {
    auto floor_div = [factor](int a) { return a >= 0 ? a / factor : -((-a + factor - 1) / factor); };
    std::map<std::array<int, 3>, std::pair<int, std::uint32_t>> cells;  // count, bead of the first fine voxel
    grid.ForEach([&](const VoxelIndex& v, const VoxelData& d) {
      auto [it, inserted] = cells.try_emplace({floor_div(v.x()), floor_div(v.y()), floor_div(v.z())}, 0, d.bead);
      ++it->second.first;
    });
    const VoxelGrid coarse = Coarsen(grid, factor);
    std::size_t expected = 0;
    for (const auto& [c, cell] : cells) {
      const bool in = 2 * cell.first >= factor * factor * factor;
      expected += in ? 1 : 0;
      const VoxelData* d = coarse.Get(VoxelIndex(c[0], c[1], c[2]));
      ASSERT_EQ(d != nullptr, in) << "factor " << factor << " at " << c[0] << " " << c[1] << " " << c[2];
      if (in) {
        EXPECT_EQ(d->bead, cell.second) << "the data of the first fine voxel, factor " << factor;
      }
    }
    EXPECT_EQ(coarse.occupied(), expected) << "factor " << factor;
  }
}

}  // namespace
}  // namespace waam::twin
