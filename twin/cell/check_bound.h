// Branch and bound on a cell check (CheckPlanBounded, the resolution's bar): the figures of a check stopped
// before it is whole, and when they prove it worse than a bar.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "planner/kinematics/cell_motion.h"
#include "twin/cell/cell_check.h"

namespace waam::twin::internal {

// Figures of the motion alone (before any collision detection): the violating samples the check will log for
// unreachable samples, joint limits and |J5| at the samples (a lower bound on its violating samples), and the
// smallest arm joint margin, axis margin and |J5| over the reachable samples (each at least the check's), deg.
struct MotionFigures {
  std::size_t violating_samples = 0;
  double min_arm_margin_deg = std::numeric_limits<double>::infinity();
  double min_joint_margin_deg = std::numeric_limits<double>::infinity();
  double min_j5_deg = std::numeric_limits<double>::infinity();
};

// The figures of `motion` checked against the limits of `kin` with the settings' joint and singularity margins.
MotionFigures MotionFiguresOf(const std::vector<planner::CellSample>& motion, const planner::CellKinematics& kin,
                              const twin::CellSettings& settings);

// Whether a check with `violating` violating samples found so far and CheckMargin terms found so far whose smallest
// is `margin_bound` (at least the whole check's CheckMargin) is proven worse than `bar`: its violating samples can
// only be more, its margin only smaller, as samples are added.
bool ProvenWorse(const CheckBar& bar, std::size_t violating, double margin_bound);

// `report` (motion planned, checks not whole) made the report of a check stopped at a bar: bounded, no violations
// listed, the motion's figures `f`, the clearance found so far `clearance_mm` (capped at the contact margin) and the
// violating samples found so far.
CheckReport BoundedReport(CheckReport report, const MotionFigures& f, double clearance_mm, std::size_t violating);

}  // namespace waam::twin::internal
