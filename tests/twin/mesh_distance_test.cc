// MeshDistance on a voxel part's surface cross-checked by brute force: distance against every facet, sign against
// the winding number of the closed surface.
#include "twin/scanner/mesh_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "twin/deposition/voxel_grid.h"
#include "twin/scanner/surface_mesh.h"

namespace waam::twin {
namespace {

using ::testing::HasSubstr;

// Distance from p to segment ab, mm.
double SegmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// Distance from p to triangle abc, mm: to the plane if the foot lies inside (barycentric test), else to an edge.
double TriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
  const Eigen::Vector3d foot = p - (p - a).dot(n) * n;
  const bool inside = (b - a).cross(foot - a).dot(n) >= 0 && (c - b).cross(foot - b).dot(n) >= 0 &&
                      (a - c).cross(foot - c).dot(n) >= 0;
  if (inside) return std::abs((p - a).dot(n));
  return std::min({SegmentDistance(p, a, b), SegmentDistance(p, b, c), SegmentDistance(p, c, a)});
}

// Winding number of the closed mesh around p (Van Oosterom & Strackee solid angles): 1 inside, 0 outside.
double WindingNumber(const planner::TriangleMesh& mesh, const Eigen::Vector3d& p) {
  double sum = 0.0;
  for (const auto& t : mesh.facets) {
    const Eigen::Vector3d a = mesh.vertices[t[0]] - p, b = mesh.vertices[t[1]] - p, c = mesh.vertices[t[2]] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return sum / (4.0 * std::numbers::pi);
}

TEST(MeshDistance, VoxelSurfaceAgreesWithBruteForce) {
  // An L-shaped block with a through-slot and a voxel touching it only along an edge: concave edges and corners,
  // where the sign comes from the edge and vertex pseudonormals.
  VoxelGrid grid(0.5, 100000);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        if ((i >= 4 && j >= 4) || (i == 2 && j >= 2 && j < 6)) continue;
        grid.Set(VoxelIndex(i, j, k), VoxelData{});
      }
  grid.Set(VoxelIndex(8, 4, 2), VoxelData{});
  const planner::TriangleMesh mesh = ExtractSurface(grid);
  ASSERT_EQ(OpenEdges(mesh), 0u) << "the test needs a closed surface for the winding number";
  const MeshDistance distance(mesh);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 5.5);
  std::uniform_real_distribution<double> near(-0.3, 0.3);
  const Eigen::Vector3i dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<Eigen::Vector3d> points;
  for (int n = 0; n < 600; ++n) points.emplace_back(u(rng), u(rng), u(rng));
  // Near the surface: voxel face centres (where the twin's scan samples), jittered.
  grid.ForEach([&](const VoxelIndex& v, const VoxelData&) {
    for (const Eigen::Vector3i& d : dirs) {
      if (grid.Solid(v + d)) continue;
      const Eigen::Vector3d c = grid.Center(v) + 0.25 * d.cast<double>();
      points.push_back(c);
      points.push_back(c + Eigen::Vector3d(near(rng), near(rng), near(rng)));
    }
  });
  int signed_checked = 0;
  for (const Eigen::Vector3d& p : points) {
    double brute = std::numeric_limits<double>::infinity();
    for (const auto& t : mesh.facets) {
      brute = std::min(brute, TriangleDistance(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]));
    }
    Eigen::Vector3d closest;
    const double d = distance.SignedDistance(p, &closest);
    ASSERT_NEAR(std::abs(d), brute, 1e-9) << "distance at " << p.transpose();
    ASSERT_NEAR((p - closest).norm(), std::abs(d), 1e-12) << "closest point at " << p.transpose();
    if (brute < 1e-6) continue;  // on the surface: either sign
    const bool inside = WindingNumber(mesh, p) > 0.5;
    ASSERT_EQ(d < 0, inside) << "sign at " << p.transpose() << " (distance " << d << ")";
    ++signed_checked;
  }
  // What the structure keeps: the tree order (4 bytes a facet) and at most one inner node (56 bytes) per 2 facets
  // (leaves hold 2-4), well under the 120 bytes a facet that per-facet normal tables would take.
  EXPECT_LE(distance.MemoryBytes(), 32 * mesh.facets.size()) << mesh.facets.size() << " facets";
  // The face centres of flat faces lie on the surface; the random and the jittered points do not.
  EXPECT_GT(signed_checked, static_cast<int>(points.size()) / 2) << "of " << points.size() << " points";
}

TEST(MeshDistance, VertexIndexOutOfRangeIsRefused) {
  planner::TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.facets = {{0, 1, 2}, {0, 2, 3}};
  try {
    MeshDistance distance(mesh);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("facet 1 refers to vertex 3 of 3"));
  }
}

}  // namespace
}  // namespace waam::twin
