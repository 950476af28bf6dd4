// Joint-angle helpers shared by the arm and positioner kinematics (radians).
#pragma once

namespace waam::planner {

// The 2 pi copy of angle `q` inside [lo, hi] nearest `target`; if no copy fits, the copy nearest `target`, so a path
// running past a limit stays continuous (and the limit check reports it).
double NearestAngleCopy(double q, double lo, double hi, double target);

}  // namespace waam::planner
