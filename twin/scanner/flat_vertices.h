// Removal of the vertices a closed mesh does not need: those inside a flat region or on a straight crease.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace waam::twin {

// Removes from a closed, manifold, outward-facing mesh on integer points every vertex whose facets lie in one plane
// (a point inside a flat region) or in two planes meeting along a straight line through it (a point on a straight
// crease), re-triangulating the hole it leaves in each plane by ear clipping without new points. The surface is
// unchanged (same point set), stays closed and manifold, has no degenerate facet and no T-junction; each removed
// vertex takes two facets with it. A vertex is kept where its facets do not form one fan (a vertex shared by two
// cones), where no valid triangulation is found, or where one would repeat an edge of the mesh. `points` are the
// vertices' coordinates (any integer unit, |coordinate| < 2^20); `facets` are rewritten, vertices visited in index
// order (deterministic). Returns the number of vertices removed; the removed ones are no longer in `facets`.
std::size_t RemoveFlatVertices(const std::vector<Eigen::Vector3i>& points, std::vector<std::array<int, 3>>* facets);

}  // namespace waam::twin
