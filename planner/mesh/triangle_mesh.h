// Indexed triangle mesh with welded vertices, and its health report.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace waam::planner {

// An indexed triangle mesh in the part frame (mm). Facets are counter-clockwise seen from outside.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> facets;
};

// What the reader found in a mesh (reported by `waam plan` and refused when the mesh cannot be sliced).
struct MeshReport {
  std::string source;               // file name or generator name
  bool binary = false;              // STL encoding
  std::size_t facets_read = 0;      // facets in the file
  std::size_t facets = 0;           // facets kept after dropping degenerate ones
  std::size_t vertices = 0;         // vertices after welding
  std::size_t degenerate_facets = 0;  // zero-area or repeated-vertex facets dropped
  std::size_t boundary_edges = 0;   // edges used by one facet (holes in the surface)
  std::size_t non_manifold_edges = 0;  // edges used by more than two facets
  std::size_t misoriented_edges = 0;  // edges whose two facets run them the same way (inconsistent normals)
  bool watertight = false;          // every edge used by exactly two facets
  double volume_mm3 = 0.0;          // enclosed volume (divergence theorem); meaningful when watertight
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero();  // mm
  Eigen::Vector3d bbox_max = Eigen::Vector3d::Zero();  // mm
  double weld_tolerance_mm = 0.0;
};

}  // namespace waam::planner
