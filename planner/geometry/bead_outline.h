// The outlines of beads swept along polylines, as Clipper paths to be filled with the positive rule, and the area of
// a region they leave uncovered.
#pragma once

#include <vector>

#include <polyclipping/clipper.hpp>

#include "planner/geometry/clipper_adapter.h"
#include "planner/geometry/polygon.h"

namespace waam::planner::internal {

// Appends to `outlines` one closed path per polyline (mm) around the area a disc of radius `radius_mm` (> 0) sweeps
// along it: Clipper's open round offset (ClipperOffset, etOpenRound with jtRound: the same round joins and caps, their
// chords within `arc_tolerance_mm` of the circle), except where the path turns away from a side: there the side's
// two offset lines meet at one point instead of a loop through the polyline's vertex, when that point lies on both
// offset segments. The union is the same area (the loop lies inside the bead) with a small fraction of Clipper's
// crossings to resolve. Each outline winds positively around its bead; fill them with pftPositive.
void AppendBeadOutlines(const std::vector<Polyline>& lines, double radius_mm, double arc_tolerance_mm,
                        ClipperLib::Paths* outlines);

// Area (mm^2) of the region `region_paths` (Clipper paths filled with the non-zero rule, e.g. ToPaths of regions)
// outside every bead of `outlines` (from AppendBeadOutlines): one Clipper pass that does the beads' union and the
// difference together.
double AreaOutsideBeads(const ClipperLib::Paths& region_paths, const ClipperLib::Paths& outlines);

}  // namespace waam::planner::internal
