// Internal helpers shared by the layer patterns: option checks, start points, rasters and move lists.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "planner/geometry/clipper_adapter.h"
#include "planner/geometry/polygon.h"
#include "planner/path/layer_pattern.h"

namespace waam::planner::internal {

// Throws InputError naming the first option that is out of range.
void ValidatePatternOptions(const PatternOptions& options);

// Fraction of a closed loop (0..1) where layer `options.layer_index` starts: a seeded offset plus the golden ratio
// per layer, so starts spread evenly along the loop and never stack on the layer below. 0 when alternation is off.
double StartFraction(const PatternOptions& options);

// Point at `fraction` (0..1) of the perimeter of `ring`, walking from ring[0].
Eigen::Vector2d PointAlongRing(const Ring& ring, double fraction);

// Appends a closed loop as one weld pass: an arc-off move to the loop point nearest `start_near`, then weld moves
// around the loop back to it. `reverse` walks the loop the other way.
void AppendLoop(const Ring& loop, const Eigen::Vector2d& start_near, bool reverse, std::vector<Move2D>* moves);

// Largest distance (mm) a welded point may be moved off the path when consecutive weld moves that run nearly
// straight on are merged into one (SimplifyMoves).
inline constexpr double kStraightPathToleranceMm = 0.05;

// How much closer to the wall (mm) than the bead centre lines a link between raster ends may run: 0.01 mm, so links
// that follow an inset boundary are not rejected for rounding, plus the contour tolerance (a simplified boundary
// turns by a larger angle at each of its fewer vertices, and a short link across a reflex vertex leaves the inset
// polygon by up to about that tolerance).
double LinkSlackMm(const PatternOptions& options);

// Merges consecutive weld moves into one wherever every point dropped between them lies within `tolerance_mm` of
// the new straight move (and between its ends). Arc-on and arc-off points and travel moves are kept as they are.
std::vector<Move2D> SimplifyMoves(const std::vector<Move2D>& moves, double tolerance_mm);

// Reverses the order of a move list, keeping each weld flag on the segment it belongs to.
std::vector<Move2D> ReverseMoves(const std::vector<Move2D>& moves);

// Raster direction (radians): the minimum-width direction of the region's convex hull when auto, else the angle.
double RasterAngle(const PolygonWithHoles& region, const PatternOptions& options);

// One clipped raster segment; `line` numbers the raster lines in order across the region.
struct RasterSegment {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  int line = 0;
};

// Parallel lines at `angle_rad`, evenly spaced at most `spacing_mm` apart from one extreme of `area` to the
// other (the first and last a hair inside), clipped to `area`.
std::vector<RasterSegment> RasterFill(const std::vector<PolygonWithHoles>& area, double angle_rad, double spacing_mm);

// True if the segment a-b lies inside `area` over its whole length (Clipper open-path clip).
bool SegmentInside(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::vector<PolygonWithHoles>& area);

// Links raster segments into zigzags: a segment on a neighbouring line is joined by a weld move when the link lies
// inside `link_area` and is at most `max_link_mm` long; otherwise the torch travels (arc off) to the nearest
// unvisited segment. Appends the moves.
void LinkRasters(std::vector<RasterSegment> segments, const std::vector<PolygonWithHoles>& link_area,
                 double max_link_mm, std::vector<Move2D>* moves);

}  // namespace waam::planner::internal
