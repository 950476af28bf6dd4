// Branch and bound on a cell check: the motion's own figures and the report of a check stopped at a bar.
#include "twin/cell/check_bound.h"

#include <algorithm>
#include <cmath>

#include "twin/cell/mujoco_cell.h"

namespace waam::twin::internal {

MotionFigures MotionFiguresOf(const std::vector<planner::CellSample>& motion, const planner::CellKinematics& kin,
                              const twin::CellSettings& settings) {
  Eigen::Matrix<double, 8, 1> lo, hi;
  lo << kin.arm.lower, kin.positioner.tilt_lower, kin.positioner.rotation_lower;
  hi << kin.arm.upper, kin.positioner.tilt_upper, kin.positioner.rotation_upper;
  MotionFigures f;
  for (const planner::CellSample& s : motion) {
    if (!s.reachable) {
      ++f.violating_samples;
      continue;
    }
    // As SampleChecks::JointLimits and Singularity log them.
    for (int j = 0; j < 8; ++j) {
      if (!planner::HasAxis(kin.positioner.type, j)) continue;
      const double m_deg = JointMarginDeg(s.q, j, lo[j], hi[j]);
      if (j < 6) f.min_arm_margin_deg = std::min(f.min_arm_margin_deg, m_deg);
      f.min_joint_margin_deg = std::min(f.min_joint_margin_deg, m_deg);
      if (m_deg < settings.joint_margin_deg) ++f.violating_samples;
    }
    const double j5_deg = J5Deg(s.q);
    f.min_j5_deg = std::min(f.min_j5_deg, j5_deg);
    if (j5_deg < settings.singularity_deg) ++f.violating_samples;
  }
  return f;
}

bool ProvenWorse(const CheckBar& bar, std::size_t violating, double margin_bound) {
  if (violating > bar.violating_samples) return true;
  return bar.violating_samples == 0 && margin_bound < bar.margin;
}

CheckReport BoundedReport(CheckReport report, const MotionFigures& f, double clearance_mm, std::size_t violating) {
  const auto finite = [](double v) { return std::isfinite(v) ? v : 0.0; };
  report.bounded = true;
  report.ok = violating == 0;
  report.violating_samples_found = violating;
  report.violations.clear();
  report.min_arm_margin_deg = finite(f.min_arm_margin_deg);
  report.min_joint_margin_deg = finite(f.min_joint_margin_deg);
  report.min_j5_deg = finite(f.min_j5_deg);
  report.min_clearance_mm = std::min(clearance_mm, CellModel::kClearanceMarginMm);
  return report;
}

}  // namespace waam::twin::internal
