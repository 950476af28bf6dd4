// Slice rings simplified to a tolerance (Ramer-Douglas-Peucker) into valid regions, before the path patterns.
#pragma once

#include <vector>

#include "planner/geometry/polygon.h"

namespace waam::planner {

// Slices are simplified to this share of the bead width before the patterns fill them (w/100: 0.02 mm for a 2 mm
// bead, 0.06 mm for a 6 mm one). A bead's own edge wanders by tenths of a millimetre, so the weld cannot tell the
// difference; a facetted mesh's slice has a vertex every facet, far more than the pattern needs.
inline constexpr double kContourToleranceFraction = 0.01;

// The points of the closed ring `ring` that Ramer-Douglas-Peucker keeps at `tolerance_mm` (>= 0): every dropped
// point lies within tolerance_mm of the edge of the result that replaced it. Keeps the order and the first point;
// a ring of fewer than 4 points, or tolerance 0, comes back as it is. Linear in the size of the ring for smooth
// curves (quadratic at worst, like every RDP).
Ring SimplifyRing(const Ring& ring, double tolerance_mm);

// The regions with every ring simplified by SimplifyRing and then made valid again by a Clipper union that keeps
// the area of positive winding: rings that crossed (where two boundaries ran closer than 2 tolerance_mm) are cut at
// the crossings, a lobe of a ring that flipped over is dropped, and where a hole crossed its outer ring the wall
// between them (thinner than 2 tolerance_mm) opens. The result: outers counter-clockwise with their holes
// clockwise, no self-intersections, every boundary within tolerance_mm of the input's. Input orientation does not
// matter (outers are taken as positive, holes as negative). Rings that shrink below 3 points are dropped.
std::vector<PolygonWithHoles> SimplifyRegions(const std::vector<PolygonWithHoles>& regions, double tolerance_mm);

}  // namespace waam::planner
