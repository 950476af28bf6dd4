// Signed distance from points to a triangle mesh: a bounding-volume hierarchy and angle-weighted pseudonormals.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "planner/mesh/triangle_mesh.h"

namespace waam::twin {

// A const query structure over a mesh (part frame, mm). The mesh must outlive it.
class MeshDistance {
 public:
  // Builds the hierarchy. Throws InputError for a mesh without facets or with a vertex index out of range.
  explicit MeshDistance(const planner::TriangleMesh& mesh);

  // Signed distance of `p` to the surface, mm: positive outside the closed surface, negative inside (the sign of
  // the angle-weighted pseudonormal at the closest feature, Baerentzen & Aanaes 2005). `closest` may be null.
  double SignedDistance(const Eigen::Vector3d& p, Eigen::Vector3d* closest = nullptr) const;

 private:
  struct Node {
    Eigen::Vector3d lo, hi;
    int left = -1;     // children, or -1 for a leaf
    int right = -1;
    int first = 0;     // leaf: range in order_
    int count = 0;
  };
  int Build(int first, int count);

  const planner::TriangleMesh& mesh_;
  std::vector<Node> nodes_;
  std::vector<int> order_;                          // facet indices, grouped by leaf
  std::vector<Eigen::Vector3d> centroid_;
  std::vector<Eigen::Vector3d> face_normal_;        // unit
  std::vector<std::array<Eigen::Vector3d, 3>> edge_normal_;  // per facet edge (v0v1, v1v2, v2v0), summed faces
  std::vector<Eigen::Vector3d> vertex_normal_;      // angle weighted
};

}  // namespace waam::twin
