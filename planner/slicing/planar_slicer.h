// Planar slicing of a closed triangle mesh into polygons with holes at given heights.
#pragma once

#include <cstddef>
#include <vector>

#include "planner/geometry/polygon.h"
#include "planner/mesh/triangle_mesh.h"

namespace waam::planner {

// What the slicer met on the way; open chains mean the mesh was not watertight.
struct SliceReport {
  std::size_t segments = 0;                 // facet/plane intersection segments over all heights
  std::size_t facet_tests = 0;              // active-set facets examined over all heights
  std::size_t open_chains = 0;              // chains that did not close (left out of the slices)
  std::vector<double> open_chain_heights_mm;  // height of each open chain
};

// Cuts `mesh` (mm, closed, manifold; facet orientation need not be consistent) with the planes z = heights_mm[i]
// (any order, finite). Returns, for each height, the regions of the cut: outer rings counter-clockwise with their
// holes clockwise, decided by nesting depth (even = outer, odd = hole; an island inside a hole is a new region), as
// in step 1 of Ding et al. 2014, section 3.1. A vertex exactly at a plane counts as above it. If a chain does not
// close it is left out and counted in `*report`; with `report` null, an open chain throws InputError instead.
// Throws InputError for a non-finite height.
std::vector<std::vector<PolygonWithHoles>> SlicePlanar(const TriangleMesh& mesh, const std::vector<double>& heights_mm,
                                                       SliceReport* report = nullptr);

// Nests closed rings (any orientation, non-crossing) into regions by depth: even depth outer (made CCW), odd depth
// a hole (made CW) of its immediate container. Rings with fewer than 3 points or zero area are dropped.
std::vector<PolygonWithHoles> NestRings(std::vector<Ring> rings);

}  // namespace waam::planner
