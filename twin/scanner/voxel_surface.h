// The part's exported surface: coplanar voxel faces merged into polygons, closed and manifold.
#pragma once

#include <cstddef>
#include <limits>

#include "planner/mesh/triangle_mesh.h"
#include "twin/deposition/voxel_grid.h"

namespace waam::twin {

// The boundary of the occupied voxels as a closed, manifold, outward-facing triangle mesh (mm, part frame) with
// coplanar voxel faces merged: the exposed faces of each plane are joined into rectangles, every corner of a
// rectangle that lies on another rectangle's edge splits that edge (no T-junction cracks), each rectangle is cut into
// triangles over its split boundary, and then every vertex inside a plane's region or on a straight crease is removed
// (RemoveFlatVertices): each plane's region is one polygon, with holes, triangulated over the corners of its outline.
// The surface is exactly the voxels' boundary; no facet is degenerate.
// Where two voxels touch along an edge only (the four faces round that edge would make it non-manifold) one of the
// two empty voxels between them is filled for the mesh, until none is left; the grid itself is not changed. The
// substrate is not part of the mesh: the part closes at z = 0. Encloses the occupied volume plus the filled voxels.
// Returns an empty mesh without merging when the part has more than `max_faces` exposed voxel faces (the caller
// then exports a coarser grid).
planner::TriangleMesh ExtractVoxelSurface(const VoxelGrid& grid,
                                          std::size_t max_faces = std::numeric_limits<std::size_t>::max());

}  // namespace waam::twin
