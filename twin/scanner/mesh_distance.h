// Signed distance from points to a triangle mesh: a bounding-volume hierarchy and angle-weighted pseudonormals.
#pragma once

#include <cstddef>
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
  // Heap memory of the query structure (the mesh not included), bytes.
  std::size_t MemoryBytes() const;

 private:
  // An inner node of the hierarchy (more than 4 facets). The tree is the median split of order_ ranges, so a node's
  // children are its range's halves; a child of at most 4 facets is a leaf, not stored (its box is recomputed from
  // its facets when needed, half the nodes of a voxel surface). An inner left child is the next node.
  struct Node {
    Eigen::Vector3d lo, hi;
    int right = -1;    // index of the right child, -1 for a leaf
  };
  int Build(int first, int count);
  // Box of the facets order_[first .. first + count), mm.
  void RangeBox(int first, int count, Eigen::Vector3d* lo, Eigen::Vector3d* hi) const;
  // The facets that have vertex `v`, ascending, into `facets`: found through the tree (their boxes hold v).
  void FacetsAt(int v, std::vector<int>* facets) const;
  // Unit normal of facet `f`; the angle-weighted pseudonormal of vertex `v`; the sum of the normals of the facets
  // along edge (a, b). Recomputed when a query needs them rather than stored (a voxel part's surface has ~10^7
  // facets), in the same order of summation as a precomputed table would be, so the values are the same.
  Eigen::Vector3d FaceNormal(int f) const;
  Eigen::Vector3d VertexNormal(int v) const;
  Eigen::Vector3d EdgeNormal(int a, int b) const;

  const planner::TriangleMesh& mesh_;
  std::vector<Node> nodes_;
  std::vector<int> order_;           // facet indices, grouped by leaf
};

}  // namespace waam::twin
