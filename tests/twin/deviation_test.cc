// Signed distance to a mesh (cross-checked by brute force) and the scan-to-target deviation of voxel parts.
#include "twin/scanner/deviation.h"

#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "tests/twin/test_paths.h"
#include "twin/scanner/mesh_distance.h"
#include "twin/scanner/scan_deviation.h"
#include "twin/scanner/surface_sample.h"
#include "twin/scanner/target_volume.h"

namespace waam::twin {
namespace {

using ::testing::HasSubstr;

TEST(MeshDistance, BoxDistancesAndSigns) {
  const planner::TriangleMesh box = testing::BoxMesh({0, 0, 0}, {10, 20, 30});
  const MeshDistance distance(box);
  EXPECT_NEAR(distance.SignedDistance({5, 10, 15}), -5.0, 1e-12) << "centre: 5 mm inside the nearest face";
  EXPECT_NEAR(distance.SignedDistance({12, 10, 15}), 2.0, 1e-12) << "2 mm outside the x = 10 face";
  EXPECT_NEAR(distance.SignedDistance({13, 24, 15}), 5.0, 1e-12) << "outside an edge: 3-4-5";
  EXPECT_NEAR(distance.SignedDistance({-1, -2, -2}), 3.0, 1e-12) << "outside a corner: 1-2-2";
  // Brute force |distance| over random points; sign from the box itself.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-5.0, 35.0);
  for (int n = 0; n < 500; ++n) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const Eigen::Vector3d q = p.cwiseMax(Eigen::Vector3d::Zero()).cwiseMin(Eigen::Vector3d(10, 20, 30));
    const bool inside = (p.array() > 0).all() && p.x() < 10 && p.y() < 20 && p.z() < 30;
    const double expected = inside ? -std::min({p.x(), 10 - p.x(), p.y(), 20 - p.y(), p.z(), 30 - p.z()})
                                   : (p - q).norm();
    ASSERT_NEAR(distance.SignedDistance(p), expected, 1e-9) << "at " << p.transpose();
  }
}

TEST(MeshDistance, EmptyMeshIsRefused) {
  try {
    MeshDistance distance{planner::TriangleMesh{}};
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no facets"));
  }
}

// Two flat patches over a box's top: a large one 1 mm above it in two facets, a small one 3 mm above it in 40
// slivers (far more points per mm^2). Per unit area, mean = (1600 x 1 + 100 x 3) / 1700 mm and
// rms = sqrt((1600 x 1 + 100 x 9) / 1700) mm, whatever the facets.
TEST(ScanDeviation, SampledSurfaceIsWeightedByArea) {
  const planner::TriangleMesh target = testing::BoxMesh({0, 0, -10}, {100, 100, 0});  // MeshDistance keeps a reference
  const MeshDistance distance(target);
  planner::TriangleMesh scan;
  auto quad = [&](double x0, double y0, double x1, double y1, double z) {
    const int v = static_cast<int>(scan.vertices.size());
    scan.vertices.insert(scan.vertices.end(), {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}});
    scan.facets.push_back({v, v + 1, v + 2});
    scan.facets.push_back({v, v + 2, v + 3});
  };
  quad(10, 10, 50, 50, 1.0);
  for (int i = 0; i < 20; ++i) quad(60 + 0.5 * i, 60, 60.5 + 0.5 * i, 70, 3.0);
  const SurfaceSamples samples = SampleSurfaceByArea(scan, 0.5, false);
  ASSERT_EQ(samples.points.size(), samples.area_mm2.size());
  double area = 0.0;
  for (const double a : samples.area_mm2) area += a;
  EXPECT_NEAR(area, 1700.0, 1e-6);
  const ScanDeviation weighted = MeasureScanDeviation(samples.points, distance, samples.area_mm2);
  EXPECT_NEAR(weighted.mean_mm, 1900.0 / 1700.0, 1e-9);
  EXPECT_NEAR(weighted.rms_mm, std::sqrt(2500.0 / 1700.0), 1e-9);
  // Per point, the slivers' many points pull the figures towards 3 mm: the bias the weights remove.
  const ScanDeviation per_point = MeasureScanDeviation(samples.points, distance);
  EXPECT_GT(per_point.mean_mm, weighted.mean_mm + 0.5);
  // Percentiles by area: 1600 of the 1700 mm^2 (94 %) are 1 mm out, so the 90th percentile of |d| is 1 mm and the
  // 99th 3 mm; per point (the slivers hold about 40 % of the points) the 90th is 3 mm.
  EXPECT_NEAR(AbsDeviationQuantile(weighted, 0.9), 1.0, 1e-9);
  EXPECT_NEAR(AbsDeviationQuantile(weighted, 0.99), 3.0, 1e-9);
  EXPECT_NEAR(AbsDeviationQuantile(per_point, 0.9), 3.0, 1e-9);
  EXPECT_NEAR(AbsDeviationQuantile(weighted, 0.0), 1.0, 1e-9);
  EXPECT_NEAR(AbsDeviationQuantile(weighted, 1.0), 3.0, 1e-9);
  EXPECT_THAT([&] { AbsDeviationQuantile(weighted, 1.5); }, ::testing::ThrowsMessage<InputError>(HasSubstr("[0, 1]")));
  // Kept subsets keep their weights: the small patch alone is 3 mm.
  const ScanDeviation small = KeepScanPoints(weighted, [&](std::size_t i) { return weighted.points[i].x() > 55; });
  EXPECT_NEAR(small.mean_mm, 3.0, 1e-9);
  EXPECT_THAT([&] { MeasureScanDeviation(samples.points, distance, {1.0}); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("1 weights for")));
}

// A box scanned on its plate: the face it stands on is left out, and only that one.
TEST(ScanDeviation, BottomFaceOfASampledSurfaceIsLeftOut) {
  const planner::TriangleMesh box = testing::BoxMesh({0, 0, 0}, {10, 20, 30});
  const SurfaceSamples all = SampleSurfaceByArea(box, 1.0, false);
  const SurfaceSamples seen = SampleSurfaceByArea(box, 1.0, true);
  double area_all = 0.0, area_seen = 0.0;
  for (const double a : all.area_mm2) area_all += a;
  for (const double a : seen.area_mm2) area_seen += a;
  EXPECT_NEAR(area_all, 2 * (10 * 20 + 10 * 30 + 20 * 30), 1e-9);
  EXPECT_NEAR(area_seen, area_all - 200.0, 1e-9);
  EXPECT_NEAR(seen.skipped_area_mm2, 200.0, 1e-9);
  EXPECT_EQ(all.skipped_facets, 0u);
  for (const Eigen::Vector3d& p : seen.points) EXPECT_GT(p.z(), 0.0);
  EXPECT_EQ(SampleSurface(box, 1.0).size(), all.points.size()) << "the same points as the unweighted sampler";
}

// A box on its plate whose top came out delta too high, sampled as an STL scan against the box it should be. The top
// (L x W) is delta out; the sides (perimeter P, height H + delta) are on the target up to H and z - H out above it.
// Without the bottom (the area A = L W + P (H + delta)): mean = (L W delta + P delta^2 / 2) / A and
// rms^2 = (L W delta^2 + P delta^3 / 3) / A; with it, A grows by L W and the sums stay.
TEST(ScanDeviation, BoxWithATopTooHighHasTheClosedFormRms) {
  const double l = 20.0, w = 10.0, h = 10.0, delta = 1.0, p = 2.0 * (l + w);
  const planner::TriangleMesh target = testing::BoxMesh({0, 0, 0}, {l, w, h});
  const planner::TriangleMesh built = testing::BoxMesh({0, 0, 0}, {l, w, h + delta});
  const MeshDistance distance(target);
  const double sum = l * w * delta + p * delta * delta / 2.0, sum2 = l * w * delta * delta + p * delta * delta * delta / 3.0;
  for (const bool skip_bottom : {true, false}) {
    const SurfaceSamples samples = SampleSurfaceByArea(built, 0.5, skip_bottom);
    const double area = l * w * (skip_bottom ? 1.0 : 2.0) + p * (h + delta);
    const ScanDeviation scan = MeasureScanDeviation(samples.points, distance, samples.area_mm2);
    // The centre of each sub-triangle integrates z - H exactly but for the row the kink at z = H crosses.
    EXPECT_NEAR(scan.mean_mm, sum / area, 1e-3) << "skip_bottom " << skip_bottom;
    EXPECT_NEAR(scan.rms_mm, std::sqrt(sum2 / area), 1e-3) << "skip_bottom " << skip_bottom;
    EXPECT_NEAR(scan.max_mm, delta, 1e-9);
    EXPECT_NEAR(scan.min_mm, 0.0, 1e-9);
    // The top holds L W / A of the area (23 % or 19 %), all at delta: the 90th percentile of |d| is delta, the
    // median is below the kink.
    EXPECT_NEAR(AbsDeviationQuantile(scan, 0.9), delta, 1e-9);
    EXPECT_NEAR(AbsDeviationQuantile(scan, 0.5), 0.0, 1e-9);
  }
}

// A voxel block that fills the target exactly deviates by 0; one voxel layer too many on top deviates by +1 voxel.
TEST(Deviation, ExactAndOverbuiltBlocks) {
  const planner::TriangleMesh target = testing::BoxMesh({0, 0, 0}, {5, 4, 3});
  VoxelGrid grid(0.5, 100000);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 10; ++i) grid.Set(VoxelIndex(i, j, k), VoxelData{});
  DeviationReport exact = MeasureDeviation(grid, target);
  EXPECT_EQ(exact.samples, 10u * 8u + 2u * (10u + 8u) * 6u) << "top and side faces; the bottom sits on the substrate";
  EXPECT_NEAR(exact.rms_mm, 0.0, 1e-9);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 10; ++i) grid.Set(VoxelIndex(i, j, 6), VoxelData{});
  DeviationReport over = MeasureDeviation(grid, target);
  EXPECT_NEAR(over.max_mm, 0.5, 1e-9);
  EXPECT_NEAR(over.min_mm, 0.0, 1e-9);
  // The mesh voxelizes back to the same block.
  const TargetVolume volume = TargetVolume::FromMesh(target, 0.5, 1000000);
  EXPECT_EQ(volume.CountInside(), 10u * 8u * 6u);
}

// The distances are measured in parallel: the same points, deviations and sums on 1 and 4 threads, on a block
// whose exposed faces span several of the parallel chunks, and on a seeded point cloud around it.
TEST(Deviation, SameOnOneAndFourThreads) {
  const planner::TriangleMesh target = testing::BoxMesh({0, 0, 0}, {20, 15, 10});
  VoxelGrid grid(0.25, 10000000);
  for (int k = 0; k < 44; ++k)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 76; ++i) grid.Set(VoxelIndex(i, j, k), VoxelData{});
  std::vector<Eigen::Vector3d> cloud;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 22.0);
  for (int n = 0; n < 20000; ++n) cloud.emplace_back(u(rng), 0.75 * u(rng), 0.5 * u(rng));
  const MeshDistance distance(target);
  SetThreadCount(1);
  const DeviationReport one = MeasureDeviation(grid, target);
  const ScanDeviation scan_one = MeasureScanDeviation(cloud, distance);
  SetThreadCount(4);
  const DeviationReport four = MeasureDeviation(grid, target);
  const ScanDeviation scan_four = MeasureScanDeviation(cloud, distance);
  SetThreadCount(0);
  ASSERT_GT(one.samples, 3u * 4096u) << "several chunks";
  ASSERT_EQ(one.samples, four.samples);
  for (std::size_t i = 0; i < one.points.size(); ++i) {
    ASSERT_EQ(one.points[i].p_P, four.points[i].p_P) << i;
    ASSERT_EQ(one.points[i].deviation_mm, four.points[i].deviation_mm) << i;
  }
  EXPECT_EQ(one.rms_mm, four.rms_mm);
  EXPECT_EQ(one.mean_mm, four.mean_mm);
  EXPECT_GT(one.max_mm, 0.0) << "the block stands 1 mm over the target";
  EXPECT_EQ(scan_one.deviation_mm, scan_four.deviation_mm);
  EXPECT_EQ(scan_one.normal, scan_four.normal);
  EXPECT_EQ(scan_one.rms_mm, scan_four.rms_mm);
  EXPECT_EQ(scan_one.min_mm, scan_four.min_mm);
}

}  // namespace
}  // namespace waam::twin
