// Mesh measures and repairs shared by the STL reader, the generators and the slicer: welding, edge analysis,
// bounding box, enclosed volume and placing a part on the build plate.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/mesh/triangle_mesh.h"

namespace waam::planner {

// Builds an indexed mesh from a triangle soup (`corners` holds 3 points per facet, mm). Points closer than
// `weld_tolerance_mm` (>= 0; 0 welds only bit-identical points) are merged deterministically: each point joins the
// lowest-numbered earlier vertex within the tolerance, found through a spatial hash grid.
// Facets that repeat a vertex after welding or have zero area are dropped and counted in `*degenerate` (may be null),
// and vertices used only by them are removed.
TriangleMesh WeldTriangles(const std::vector<Eigen::Vector3d>& corners, double weld_tolerance_mm,
                           std::size_t* degenerate);

// Fills a report for an indexed mesh as it is (no welding; `weld_tolerance_mm` is only recorded): facet and vertex
// counts, bounding box, boundary / non-manifold / misoriented edge counts, watertightness and enclosed volume.
// `source` names the file or generator in messages.
MeshReport InspectMesh(const TriangleMesh& mesh, double weld_tolerance_mm, const std::string& source);

// Axis-aligned bounding box of the vertices (mm); both zero for an empty mesh.
void BoundingBox(const TriangleMesh& mesh, Eigen::Vector3d* min, Eigen::Vector3d* max);

// Signed enclosed volume in mm^3 by the divergence theorem (sum of signed tetrahedra to the origin); positive for a
// closed mesh with outward normals.
double EnclosedVolume(const TriangleMesh& mesh);

// Translates the mesh so that its lowest point is at z = 0; returns the shift applied along z (mm).
double PlaceOnBuildPlate(TriangleMesh* mesh);

// Translates every vertex by `offset_mm`.
void Translate(TriangleMesh* mesh, const Eigen::Vector3d& offset_mm);

// True if the facet has zero area (its cross product vanishes relative to its longest edge squared).
bool IsDegenerateFacet(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace waam::planner
