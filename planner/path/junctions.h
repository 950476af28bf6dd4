// Junctions of a rib-web layer path: the turning points at cell corners, their angles and the junction class.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/geometry/polygon.h"
#include "planner/path/layer_pattern.h"

namespace waam::planner {

// A turning point P of the path at a corner of a cell (a re-entrant corner of the slice): the path A-P-B turns
// around the cell, and the junction's metal lies on the far side of P (003 Fig. 28).
struct TurningPoint {
  std::size_t move = 0;                          // index of P in the move list
  Eigen::Vector2d p = Eigen::Vector2d::Zero();   // mm
  double theta_rad = 0.0;                        // angle APB, radians in (0, pi)
  Eigen::Vector2d into_junction = Eigen::Vector2d::Zero();  // unit bisector pointing away from the cell (P -> P_o)
};

// One junction: the turning points around it and its class as Appendix A1 lists them.
struct Junction {
  std::vector<TurningPoint> turning_points;      // eta = turning_points.size()
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // mean of the turning points, mm
  int ribs = 0;                                  // walls meeting at the junction
  std::vector<double> angles_deg;                // angles between neighbouring ribs, descending, summing to 360

  // "<ribs> ribs <a1>/<a2>/..." with the angles rounded to whole degrees, e.g. "4 ribs 90/90/90/90".
  std::string ClassName() const;
  // Index into turning_points of the smallest angle (theta_min of eq. 4.6).
  std::size_t SharpestTurn() const;
};

// Turning points (weld on both sides, angle below 170 degrees) of `moves` whose cell side lies outside `slice`,
// grouped into junctions: points closer than 2 bead widths (`bead_width_mm`, > 0) belong to one junction. A
// junction whose cell corners add up to less than 360 degrees gets one more rib closing the circle (a wall that runs
// straight through, as at a T junction on the outer wall). Only junctions of at least `min_ribs` ribs are returned.
std::vector<Junction> FindJunctions(const std::vector<PolygonWithHoles>& slice, const std::vector<Move2D>& moves,
                                    double bead_width_mm, int min_ribs);

}  // namespace waam::planner
