// Internal bridge to ClipperLib 6.4: conversions, inward offsets, booleans and open-path clipping in millimetres.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <polyclipping/clipper.hpp>

#include "planner/geometry/polygon.h"

namespace waam::planner::internal {

// Clipper works on 64-bit integers. 1e4 units per mm gives a 0.1 um grid, far below any bead or robot tolerance,
// and keeps parts up to +-107 m inside Clipper's fast 62-bit range (loRange = 2^30 units).
inline constexpr double kClipperUnitsPerMm = 1e4;
// Largest distance (mm) between a round join or cap and its chords. 0.05 mm makes a 90 degree turn of a 3 mm
// radius (w/2 of a 6 mm bead) 4 chords (0.02 mm made it 7), so round corners add few path elements; the chord
// error is far below the bead's own waviness (a few tenths of a mm), so the weld does not see it.
inline constexpr double kArcToleranceMm = 0.05;

// An open polyline in the slice plane (mm).
using Polyline = std::vector<Eigen::Vector2d>;

ClipperLib::IntPoint ToClipper(const Eigen::Vector2d& p_mm);
Eigen::Vector2d FromClipper(const ClipperLib::IntPoint& p);

// A ring as a Clipper path; `positive` forces the orientation (true: CCW / positive area).
ClipperLib::Path ToPath(const Ring& ring, bool positive);
Ring FromPath(const ClipperLib::Path& path);

// Regions as Clipper paths with outers positive (CCW) and holes negative (CW), whatever the input orientation.
ClipperLib::Paths ToPaths(const PolygonWithHoles& region);
ClipperLib::Paths ToPaths(const std::vector<PolygonWithHoles>& regions);

// Regions from a Clipper PolyTree: every outer (CCW) with its direct holes (CW); islands in holes become regions.
std::vector<PolygonWithHoles> FromPolyTree(const ClipperLib::PolyTree& tree);

// Offsets regions by `delta_mm` (negative: inward) with round joins. Round joins (jtRound) are used because the
// centre line of a bead that keeps a constant distance from a wall must follow an arc around a re-entrant corner:
// a miter corner would sit sqrt(2) times farther from a 90 degree notch and leave it unfilled. Convex corners of
// an inward offset stay sharp in either case.
std::vector<PolygonWithHoles> Offset(const std::vector<PolygonWithHoles>& regions, double delta_mm);

// Boolean operations on regions (non-zero fill).
std::vector<PolygonWithHoles> Union(const std::vector<PolygonWithHoles>& regions);
std::vector<PolygonWithHoles> Intersection(const std::vector<PolygonWithHoles>& a,
                                           const std::vector<PolygonWithHoles>& b);
std::vector<PolygonWithHoles> Difference(const std::vector<PolygonWithHoles>& a,
                                         const std::vector<PolygonWithHoles>& b);

// The parts of open polylines that lie inside `regions` (Clipper open-path intersection).
std::vector<Polyline> ClipPolylines(const std::vector<Polyline>& lines, const std::vector<PolygonWithHoles>& regions);

// The area swept by a disc of radius `radius_mm` moved along each polyline (round caps and joins, their chords within
// `arc_tolerance_mm` of the circle).
std::vector<PolygonWithHoles> BufferPolylines(const std::vector<Polyline>& lines, double radius_mm,
                                              double arc_tolerance_mm = kArcToleranceMm);

// Length of a polyline in mm.
double Length(const Polyline& line);

}  // namespace waam::planner::internal
