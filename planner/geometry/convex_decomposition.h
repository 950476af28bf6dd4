// Convex decomposition of slice regions by notch elimination and minimum-width directions (Ding et al. 2014, 3.1-3.2).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/geometry/polygon.h"

namespace waam::planner {

// A line along which two convex pieces of a decomposition touch (mm). `on_outline` is true when the end `a` lies
// on the region's boundary (outline or hole), where Ding et al. 3.3 place the connections between pieces.
struct SharedEdge {
  int piece_a = 0;
  int piece_b = 0;
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  bool a_on_boundary = false;
};

// The outcome of a convex decomposition (a result with a status, as Ceres' Summary): the pieces, or why degenerate
// geometry defeated the notch elimination (a limit of the method on such input, not a bug and not bad input).
struct ConvexDecomposition {
  std::vector<Ring> pieces;  // convex, CCW, tiling the region; empty when !ok()
  std::string failure;       // "" on success, else what stopped it, e.g. "no usable cut for a notch"
  bool ok() const { return failure.empty(); }
};

// Splits `region` (outer CCW, holes CW; either orientation is accepted) into convex pieces, returned CCW, by
// eliminating notches (vertices with an interior angle > pi) one at a time, the largest angle first: notch-notch,
// notch-vertex and notch-line cuts (Ding et al. 2014, 3.1). Holes are merged into the outline by the same cuts.
// The pieces tile the region: no overlaps, areas sum to Area(region). Throws InputError for a region with fewer
// than 3 distinct outer vertices. When degenerate geometry leaves a notch without a usable cut the result is not
// ok() and says why: the continuous pattern then plans that region with the hybrid pattern and reports it.
ConvexDecomposition DecomposeConvex(const PolygonWithHoles& region);

// The lines along which pieces of a decomposition of `region` touch, longest first (pieces from DecomposeConvex).
std::vector<SharedEdge> FindSharedEdges(const std::vector<Ring>& pieces, const PolygonWithHoles& region);

// `ring` (the region on its left: an outline CCW, a hole CW) with its shallow notches cut off: notch vertices are
// dropped while every dropped point lies within `depth_mm` (>= 0) of the chord that replaces it, so a tessellated
// concave curve becomes chords at most `depth_mm` outside it. Convex vertices are kept: the region only grows, by at
// most `depth_mm`. Keeps the ring's orientation and at least 3 vertices.
Ring FillShallowNotches(const Ring& ring, double depth_mm);

// True if `ring` is convex: no turn against its orientation larger than `tolerance_rad` (radians).
bool IsConvex(const Ring& ring, double tolerance_rad = 1e-9);

// Direction (radians in [0, pi), from +x) of the strip of least width that holds the convex polygon `convex`,
// found with rotating calipers over the polygon's edges (Ding Lemma 1: the minimum width is attained with one side
// flush). Writes the width (mm) to `width_mm` when not null. Throws InputError for fewer than 3 distinct points.
double MinimumWidthDirection(const Ring& convex, double* width_mm);

// Convex hull of a point set (Andrew's monotone chain), CCW, without collinear points.
Ring ConvexHull(std::vector<Eigen::Vector2d> points);

}  // namespace waam::planner
