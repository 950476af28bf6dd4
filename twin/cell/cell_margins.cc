// The check's margins and the motion options and solving kinematics of the cell settings (declared in cell_check.h).
#include <algorithm>
#include <cmath>

#include "models/core/numbers.h"
#include "twin/cell/cell_check.h"

namespace waam::twin {

CheckMargins MarginsOf(const CheckReport& report) {
  CheckMargins m;
  m.violations = report.violations.size();
  for (const CheckViolation& v : report.violations) m.violating_samples += static_cast<std::size_t>(v.samples);
  m.min_arm_margin_deg = report.min_arm_margin_deg;
  m.min_j5_deg = report.min_j5_deg;
  m.min_clearance_mm = report.min_clearance_mm;
  m.max_joint_speed_ratio = report.max_joint_speed_ratio;
  return m;
}

double CheckMargin(const CheckMargins& m, const twin::CellSettings& settings) {
  return std::min({(m.min_arm_margin_deg - settings.joint_margin_deg) / 10.0,
                   (m.min_j5_deg - settings.singularity_deg) / 10.0,
                   m.min_clearance_mm / CellModel::kClearanceMarginMm});
}

double J5Deg(const planner::Joints8& q) { return std::asin(std::min(1.0, std::abs(std::sin(q[4])))) * kDeg; }

double JointMarginDeg(const planner::Joints8& q, int j, double lo, double hi) {
  return std::min(q[j] - lo, hi - q[j]) * kDeg;
}

planner::CellKinematics MarginKinematics(const planner::CellKinematics& kin, const twin::CellSettings& settings) {
  const double margin_rad = settings.joint_margin_deg / kDeg;
  planner::CellKinematics solve = kin;
  if (solve.positioner.tilt_upper - solve.positioner.tilt_lower > 2.0 * margin_rad) {
    solve.positioner.tilt_lower += margin_rad;
    solve.positioner.tilt_upper -= margin_rad;
  }
  if (solve.positioner.rotation_upper - solve.positioner.rotation_lower > 2.0 * margin_rad) {
    solve.positioner.rotation_lower += margin_rad;
    solve.positioner.rotation_upper -= margin_rad;
  }
  return solve;
}

planner::MotionOptions MotionOptionsOf(const twin::CellSettings& settings, double rapid_speed_mm_s) {
  planner::MotionOptions options;
  options.step_mm = settings.step_mm;
  options.rapid_speed_mm_s = rapid_speed_mm_s;
  options.rotation_rad = settings.positioner_rotation_deg / kDeg;
  options.positioner_per_point = settings.positioner_follow == twin::PositionerFollow::kPoint;
  options.tilt_tolerance_rad = settings.positioner_tilt_tolerance_deg / kDeg;
  return options;
}

}  // namespace waam::twin
