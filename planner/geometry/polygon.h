// Planar polygon types shared by slicing and path planning (millimetres, part frame).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace waam::planner {

// A closed ring of points; the last point is NOT repeated. Orientation carries meaning:
// counter-clockwise (positive signed area) for outer boundaries, clockwise for holes.
using Ring = std::vector<Eigen::Vector2d>;

// One connected region of a slice: an outer boundary (CCW) and the holes inside it (CW), as in Ding et al.
// step 1 (outer/inner contours found by nesting depth).
struct PolygonWithHoles {
  Ring outer;
  std::vector<Ring> holes;
};

// Signed area of a ring in mm^2 (shoelace formula); positive when counter-clockwise.
double SignedArea(const Ring& ring);

// Area of a region in mm^2: |outer| minus the holes.
double Area(const PolygonWithHoles& region);

// Total area of a slice in mm^2.
double Area(const std::vector<PolygonWithHoles>& regions);

// True if `p` lies inside `ring` (even-odd rule; points on the boundary may go either way).
bool PointInRing(const Eigen::Vector2d& p, const Ring& ring);

// Perimeter of a closed ring in mm.
double Perimeter(const Ring& ring);

// `regions` offset by `delta_mm` (negative: inward) with round joins, as every planner offsets (ClipperLib,
// planner/geometry/clipper_adapter.h).
std::vector<PolygonWithHoles> OffsetRegions(const std::vector<PolygonWithHoles>& regions, double delta_mm);

}  // namespace waam::planner
