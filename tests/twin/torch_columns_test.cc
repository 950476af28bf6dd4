// Tests of the torch-frame footprint columns: a grid-aligned torch gets the grid's own columns, a tilted one a
// partition of the voxels into columns along its axis (no voxel twice, none skipped).
#include "twin/deposition/torch_columns.h"

#include <cmath>
#include <random>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

namespace waam::twin::internal {
namespace {

TEST(TorchColumns, AlignedTorchGetsTheGridColumns) {
  const double v = 0.5;
  std::vector<ColumnVoxel> out;
  TorchFrame(Eigen::Vector3d::UnitZ(), v).CollectColumn(3, -2, 0.0, 5.0, &out);
  ASSERT_EQ(out.size(), 10u) << "voxel centres at 0.25 ... 4.75 mm";
  for (std::size_t m = 0; m < out.size(); ++m) {
    EXPECT_EQ(out[m].index, VoxelIndex(3, -2, static_cast<int>(m)));
    EXPECT_DOUBLE_EQ(out[m].height_mm, (m + 0.5) * v);
  }
  // A torch along -x: the column grows towards -x, its lattice axes are y and z.
  out.clear();
  TorchFrame(-Eigen::Vector3d::UnitX(), v).CollectColumn(1, 4, 0.0, 1.0, &out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].index, VoxelIndex(-1, 1, 4));
  EXPECT_EQ(out[1].index, VoxelIndex(-2, 1, 4));
}

// Every voxel whose centre lies within 2 mm of the origin is in exactly one column of a tilted torch, at the height
// of its centre along the axis, and every column is sorted by height.
TEST(TorchColumns, TiltedColumnsPartitionTheVoxels) {
  const double v = 0.5;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d tool(gauss(rng), gauss(rng), gauss(rng));
    const TorchFrame frame(tool, v);
    std::vector<ColumnVoxel> all;
    for (int i0 = -8; i0 <= 8; ++i0) {
      for (int i1 = -8; i1 <= 8; ++i1) {
        const std::size_t first = all.size();
        frame.CollectColumn(i0, i1, -4.0, 4.0, &all);
        for (std::size_t k = first; k < all.size(); ++k) {
          const Eigen::Vector3d c = (all[k].index.cast<double>() + Eigen::Vector3d::Constant(0.5)) * v;
          const Eigen::Vector2d q = frame.Plane(c);
          EXPECT_EQ(static_cast<int>(std::floor(q.x() / v)), i0) << "voxel outside its lattice cell";
          EXPECT_EQ(static_cast<int>(std::floor(q.y() / v)), i1);
          EXPECT_NEAR(all[k].height_mm, frame.Height(c), 1e-12);
          if (k > first) {
            EXPECT_LE(all[k - 1].height_mm, all[k].height_mm) << "column not sorted by height";
          }
        }
      }
    }
    std::set<std::tuple<int, int, int>> seen;
    for (const ColumnVoxel& c : all) {
      EXPECT_TRUE(seen.insert({c.index.x(), c.index.y(), c.index.z()}).second) << "voxel in two columns";
    }
    int inside = 0;
    for (int i = -6; i <= 6; ++i) {
      for (int j = -6; j <= 6; ++j) {
        for (int k = -6; k <= 6; ++k) {
          const Eigen::Vector3d c = (Eigen::Vector3d(i, j, k) + Eigen::Vector3d::Constant(0.5)) * v;
          if (c.norm() > 2.0) continue;
          ++inside;
          EXPECT_EQ(seen.count({i, j, k}), 1u) << "voxel " << i << " " << j << " " << k << " skipped, torch "
                                               << tool.normalized().transpose();
        }
      }
    }
    EXPECT_GT(inside, 200);
  }
}

}  // namespace
}  // namespace waam::twin::internal
