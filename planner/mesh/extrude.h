// Building blocks of the procedural parts: planar rings and the extrusion of polygons with holes into closed meshes.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "planner/geometry/polygon.h"
#include "planner/mesh/triangle_mesh.h"

namespace waam::planner {

// Regular polygon of `segments` (>= 3) points on a circle of `radius_mm` around `center_mm`, counter-clockwise,
// the first point at angle 0.
Ring CircleRing(const Eigen::Vector2d& center_mm, double radius_mm, int segments);

// Axis-aligned rectangle [x0, x1] x [y0, y1] (mm), counter-clockwise.
Ring RectangleRing(double x0, double y0, double x1, double y1);

// Extrudes each region (outer and holes in either orientation; regions disjoint) from z0_mm to z1_mm (> z0_mm).
// The result is closed, with outward facet normals and shared vertices: side walls as two triangles per ring edge
// and caps triangulated by ear clipping over the same ring vertices. Throws InputError if a region cannot be
// triangulated.
TriangleMesh ExtrudeRegions(const std::vector<PolygonWithHoles>& regions, double z0_mm, double z1_mm);

// Appends `part` to `mesh` (vertex ids shifted).
void AppendMesh(const TriangleMesh& part, TriangleMesh* mesh);

}  // namespace waam::planner
