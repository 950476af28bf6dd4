// Radius and nearest-point queries over a point cloud, its cell keys, and the radius outlier removal of the scan.
#include "twin/scanner/point_hash.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "models/core/error.h"

namespace waam::twin {
namespace {

// Exposed face centres of a solid block of 12 x 12 x 4 voxels of 0.5 mm (edges and corners included), plus the six
// face centres of one voxel floating 5 mm above it. The first `*block` points are the block's.
std::vector<Eigen::Vector3d> BlockAndSpeck(std::size_t* block = nullptr) {
  std::vector<Eigen::Vector3d> points;
  const Eigen::Vector3i n(12, 12, 4);
  auto inside = [&](const Eigen::Vector3i& v) { return (v.array() >= 0).all() && (v.array() < n.array()).all(); };
  for (int z = 0; z < n.z(); ++z) {
    for (int y = 0; y < n.y(); ++y) {
      for (int x = 0; x < n.x(); ++x) {
        const Eigen::Vector3i v(x, y, z);
        for (int a = 0; a < 3; ++a) {
          for (int sign : {-1, 1}) {
            if (inside(v + sign * Eigen::Vector3i::Unit(a))) continue;
            points.push_back(0.5 * (v.cast<double>() + Eigen::Vector3d::Constant(0.5)) +
                             0.25 * sign * Eigen::Vector3d::Unit(a));
          }
        }
      }
    }
  }
  if (block != nullptr) *block = points.size();
  const Eigen::Vector3d c(3.0, 3.0, 7.0);
  for (int a = 0; a < 3; ++a) {
    points.push_back(c + 0.25 * Eigen::Vector3d::Unit(a));
    points.push_back(c - 0.25 * Eigen::Vector3d::Unit(a));
  }
  return points;
}

TEST(PointHashTest, ForEachNearFindsExactlyThePointsInTheBall) {
  const std::vector<Eigen::Vector3d> points = BlockAndSpeck();
  const PointHash hash(points, 0.7);
  const Eigen::Vector3d q(2.6, 3.1, 0.2);
  std::vector<int> found;
  hash.ForEachNear(q, 1.3, [&](int i) { found.push_back(i); });
  std::sort(found.begin(), found.end());
  std::vector<int> expected;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if ((points[i] - q).norm() <= 1.3) expected.push_back(static_cast<int>(i));
  }
  EXPECT_EQ(found, expected);
  EXPECT_EQ(hash.CountNear(q, 1.3, 1000), static_cast<int>(expected.size()));
  EXPECT_EQ(hash.CountNear(q, 1.3, 3), 3) << "the count stops at the cap";
}

TEST(PointHashTest, ForEachNearStopsWhenTheVisitorReturnsFalse) {
  const std::vector<Eigen::Vector3d> points = BlockAndSpeck();
  const PointHash hash(points, 0.7);
  const Eigen::Vector3d q(2.6, 3.1, 0.2);
  int all = 0;
  EXPECT_TRUE(hash.ForEachNear(q, 1.3, [&](int) { return ++all > 0; })) << "a visitor that never says stop sees all";
  ASSERT_GT(all, 3) << "the query ball must hold more points than the stop below";
  int visited = 0;
  EXPECT_FALSE(hash.ForEachNear(q, 1.3, [&](int) { return ++visited < 3; })) << "the search reports that it stopped";
  EXPECT_EQ(visited, 3) << "no point is visited after the visitor returned false";
}

TEST(PointHashTest, NearestAgreesWithABruteForceSearch) {
  const std::vector<Eigen::Vector3d> points = BlockAndSpeck();
  const PointHash hash(points, 0.7);
  auto brute = [&](const Eigen::Vector3d& q, double max_mm) {
    int best = -1;
    double best2 = max_mm * max_mm;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double d2 = (points[i] - q).squaredNorm();
      if (d2 <= best2 && (best < 0 || d2 < (points[best] - q).squaredNorm())) {
        best = static_cast<int>(i);
        best2 = d2;
      }
    }
    return best;
  };
  // Inside the block, beside it, between the block and the speck, and far from everything.
  for (const Eigen::Vector3d& q : {Eigen::Vector3d(2.6, 3.1, 0.2), Eigen::Vector3d(-1.3, 2.0, 1.1),
                                   Eigen::Vector3d(3.1, 2.9, 4.4), Eigen::Vector3d(40.0, 0.0, 0.0)}) {
    for (double max_mm : {0.4, 3.0, 10.0}) {
      const int found = hash.Nearest(q, max_mm);
      const int expected = brute(q, max_mm);
      ASSERT_EQ(found < 0, expected < 0) << "query " << q.transpose() << " within " << max_mm << " mm";
      if (expected >= 0) {
        EXPECT_DOUBLE_EQ((points[found] - q).norm(), (points[expected] - q).norm())
            << "query " << q.transpose() << " within " << max_mm << " mm: not the nearest point";
      }
    }
  }
}

TEST(PointHashTest, AddedPointsAreNumberedAndFoundLikeGivenOnes) {
  const std::vector<Eigen::Vector3d> points = BlockAndSpeck();
  const PointHash given(points, 0.7);
  PointHash added(0.7);
  for (std::size_t i = 0; i < points.size(); ++i) ASSERT_EQ(added.Add(points[i]), static_cast<int>(i));
  ASSERT_EQ(added.size(), points.size());
  const Eigen::Vector3d q(2.6, 3.1, 0.2);
  std::vector<int> a, b;
  given.ForEachNear(q, 1.3, [&](int i) { a.push_back(i); });
  added.ForEachNear(q, 1.3, [&](int i) { b.push_back(i); });
  EXPECT_EQ(a, b) << "same points, same visiting order";
  EXPECT_EQ(added.point(5), points[5]);
}

TEST(PointHashTest, CellKeysAreOneToOneAroundTheOrigin) {
  for (const Eigen::Vector3i& c : {Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(-1, 2, -3),
                                   Eigen::Vector3i((1 << 20) - 1, -(1 << 20), 7)}) {
    EXPECT_EQ(CellOfKey(CellKey(c)), c) << "cell " << c.transpose();
  }
  EXPECT_NE(CellKey(Eigen::Vector3i(1, 0, 0)), CellKey(Eigen::Vector3i(0, 1, 0)));
  EXPECT_NE(CellKey(Eigen::Vector3i(0, 1, 0)), CellKey(Eigen::Vector3i(0, 0, 1)));
  EXPECT_EQ(CellOf(Eigen::Vector3d(-0.1, 1.0, 2.9), 1.0), Eigen::Vector3i(-1, 1, 2)) << "floor, not truncation";
}

TEST(PointHashTest, OutlierRemovalDropsALoneVoxelAndKeepsTheSurface) {
  std::size_t block = 0;
  const std::vector<Eigen::Vector3d> points = BlockAndSpeck(&block);
  const std::vector<std::size_t> keep = DenseScanPoints(points, 1.0, 8);
  ASSERT_EQ(keep.size(), block) << "every sample of the block (edges and corners included) and none of the speck";
  for (std::size_t i : keep) EXPECT_LT(i, block);
}

TEST(PointHashTest, RejectsANonPositiveCell) {
  const std::vector<Eigen::Vector3d> points = BlockAndSpeck();
  try {
    PointHash hash(points, 0.0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("must be > 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace waam::twin
