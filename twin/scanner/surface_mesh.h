// Surface of the simulated part as a closed triangle mesh (marching tetrahedra over the voxel occupancy).
#pragma once

#include "planner/mesh/triangle_mesh.h"
#include "twin/deposition/voxel_grid.h"

namespace waam::twin {

// Extracts the iso-surface 0.5 of the occupancy sampled at voxel centres, splitting every cell into six tetrahedra
// around its main diagonal (a consistent Kuhn split, so the surface is closed and has no ambiguous cases). Vertices
// are edge midpoints, welded; facets face outward. The substrate is not part of the mesh: the part closes at z = 0.
planner::TriangleMesh ExtractSurface(const VoxelGrid& grid);

// Number of voxel faces between metal and air (faces on the substrate excluded): the size of the part's surface.
std::size_t ExposedFaces(const VoxelGrid& grid);

// The grid at `factor` (>= 1) times the voxel size: a coarse voxel is occupied when at least half of its factor^3
// fine voxels are (it keeps the data of one of them). Used to keep the exported surface of large parts small.
// Throws InputError for factor < 1.
VoxelGrid Coarsen(const VoxelGrid& grid, int factor);

// Number of edges not shared by exactly two facets (0 for a closed manifold surface).
std::size_t OpenEdges(const planner::TriangleMesh& mesh);

}  // namespace waam::twin
