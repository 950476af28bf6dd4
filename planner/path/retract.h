// Arc-off travel as a robot program runs it: lift along the torch axis, travel clear of the part, come down along
// the next start's torch axis.
#pragma once

#include <cstddef>

#include <Eigen/Core>

#include "planner/path/tool_path.h"

namespace waam::planner {

// What AddRetracts did.
struct RetractReport {
  std::size_t travels = 0;  // arc-off travels rebuilt (the approach to the first pass included)
  std::size_t via_top = 0;  // of those, routed over the top of the deposited part's bounding box
};

// Rebuilds every arc-off travel of `plan` (part frame P, mm). After each pass the TCP lifts `clearance_mm` along
// the torch axis of the pass's last point; before each pass it comes down `clearance_mm` along the torch axis of the
// pass's first point (the first pass gets the approach, the last pass the lift). Between the two, the planner's own
// travel points (the cone planner's densified travel along the surface) are kept, lifted by `clearance_mm` along
// their torch axes, as long as that travel stays at least `clearance_mm` from every TCP segment welded before it;
// otherwise the TCP leaves the bounding box of what is welded (grown by `clearance_mm`) along the torch axis, rises
// to the box's top (+z of P, away from the plate), crosses over it and comes down the same way to the next start.
// Weld points are not touched; the lift is the last point of its pass's layer, the rest belongs to the next pass's
// layer (so the positioner turns into a new layer while the torch is clear). clearance_mm <= 0 leaves the plan as
// it is.
RetractReport AddRetracts(double clearance_mm, Plan* plan);

namespace internal {

// Smallest distance (mm) between the segments a0-a1 and b0-b1 (points in mm; zero-length segments allowed).
double SegmentDistance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                       const Eigen::Vector3d& b1);

// Smallest distance (mm) from the segment p-q to the TCP segments welded in `plan` before point `before` of layer
// `layer` (weld moves only), or `limit_mm` when none is closer. Brute force; for tests.
double DistanceToWelded(const Plan& plan, std::size_t layer, std::size_t before, const Eigen::Vector3d& p,
                        const Eigen::Vector3d& q, double limit_mm);

}  // namespace internal

}  // namespace waam::planner
