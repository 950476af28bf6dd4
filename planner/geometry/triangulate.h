// Triangulation of a planar polygon with holes by ear clipping after bridging the holes into the outer ring.
#pragma once

#include <array>
#include <vector>

#include "planner/geometry/polygon.h"

namespace waam::planner {

// Triangulates `region` (mm; outer and holes simple, disjoint, holes strictly inside the outer ring, either
// orientation). Vertices are numbered as the rings are listed: the outer ring first, then each hole in order.
// Returns counter-clockwise triangles (seen from +z) that use only those vertices, so the caps of an extrusion
// share every boundary vertex with its side walls. Throws InputError if a ring has fewer than 3 points or the
// region cannot be triangulated (self-intersecting or overlapping rings).
std::vector<std::array<int, 3>> TriangulateRegion(const PolygonWithHoles& region);

}  // namespace waam::planner
