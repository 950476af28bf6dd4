// Internal: the closed contour + zigzag loop that fills one convex piece (Ding et al. 2014, section 3.2).
#pragma once

#include <vector>

#include "planner/geometry/polygon.h"
#include "planner/path/layer_pattern.h"

namespace waam::planner::internal {

// Closed loop (last point not repeated, mm) that fills the convex `piece` (CCW) with zigzag lines at `angle_rad` (radians
// from +x): contour w/2 inside the piece on one chain, zigzag lines l apart whose ends reach the contour on that
// chain and stop d1 short of it on the other. Edge k of the piece (piece[k] -> piece[k+1]) flagged in `shared`
// (empty: none) is a line it shares with a neighbouring piece, not a wall: the contour runs l/2 inside it and the
// rasters stop l short of that contour, so the beads of the two pieces lie l apart like any neighbouring beads.
// Empty when the piece is narrower than one bead.
Ring ConvexPieceLoop(const Ring& piece, double angle_rad, const OverlapSpacing& spacing,
                     const std::vector<bool>& shared = {});

}  // namespace waam::planner::internal
