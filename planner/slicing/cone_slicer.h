// Slicing a triangle mesh with a cone or cylinder (Dai et al. 2020 sec. 2.1) and flattening the contours of a layer
// onto the plane for filling (sec. 2.2).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/geometry/polygon.h"
#include "planner/mesh/triangle_mesh.h"
#include "planner/slicing/cone_surface.h"

namespace waam::planner {

// A closed contour on the surface (mm, part frame); the last point is not repeated.
using Contour3d = std::vector<Eigen::Vector3d>;

// What the intersection found, for tests and reports.
struct ConeSliceStats {
  std::array<std::size_t, 4> facets_with_segments = {0, 0, 0, 0};  // facets cut into 0, 1, 2 and 3 segments
  std::size_t edge_points = 0;      // intersection points on edges (eq. 1 with eq. 2)
  std::size_t open_chains = 0;      // chains that did not close (the mesh had holes); dropped
  double surface_shift_mm = 0.0;    // radius nudge applied because a vertex lay on the surface (step 0)
};

// Intersects `mesh` with `surface` and merges the segments into closed contours (steps 0-4 of sec. 2.1.2).
// Each edge meets the quadric in at most two points; each facet is cut into one to three segments.
// `stats` may be null.
std::vector<Contour3d> SliceWithCone(const TriangleMesh& mesh, const ConeSurface& surface, ConeSliceStats* stats);

// The contours of one layer flattened onto the plane: the regions to fill and the rotation used.
struct FlatLayer {
  std::vector<PolygonWithHoles> regions;  // even-odd nesting of the flattened contours, mm
  double alpha = 0.0;                     // rotation about the axis before flattening, rad (multiple of the step)
  bool ok = false;                        // false: every rotation left a contour across the cutting line
  std::string message;                    // why not ok
};

// Flattens `contours` of `surface` (sec. 2.2): tries alpha = 0, step, 2 step, ... below 2 pi until no contour
// crosses the cutting line (Dai uses 11 deg), then nests the flattened rings into regions (even-odd).
// A contour that winds around the axis can be cut by no rotation: ok = false with a message.
FlatLayer FlattenLayer(const std::vector<Contour3d>& contours, const ConeSurface& surface, double step_rad);

}  // namespace waam::planner
