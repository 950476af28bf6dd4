// The check's margins, and the cell model, kinematics and motion options of the cell settings (declared in
// cell_check.h).
#include <algorithm>
#include <cmath>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/cell_compose.h"
#include "twin/cell/cell_presets.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {
namespace {

Eigen::Isometry3d PlacementPose(const std::array<double, 3>& p_mm, double yaw_deg) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translate(Eigen::Vector3d(p_mm[0], p_mm[1], p_mm[2]));
  X.rotate(Eigen::AngleAxisd(yaw_deg / kDeg, Eigen::Vector3d::UnitZ()));
  return X;
}

}  // namespace

CellModel BuildCell(const CellSettings& settings, const CellFiles& files) {
  const Eigen::Isometry3d X_WR = PlacementPose(settings.robot_base_mm, settings.robot_yaw_deg);
  const Eigen::Isometry3d X_WB = PlacementPose(settings.positioner_base_mm, settings.positioner_yaw_deg);
  const planner::PositionerType type = settings.positioner_type.value_or(planner::PositionerType::kTiltRotate);
  const bool builtin = settings.preset ? PresetUrdf(*settings.preset).empty()
                                       : settings.robot_urdf.empty() && settings.mjcf.empty();
  if (builtin && type != planner::PositionerType::kTiltRotate) {
    // The built-in arm with another positioner: the file's text with the positioner composed in.
    CellModel::RobotInfo info{.name = "FANUC ARC Mate 100iC/12", .source = "builtin"};
    if (settings.preset) {
      info = {.name = std::string(PresetInfo(*settings.preset).robot_name),
              .source = std::string(NameOf(*settings.preset))};
    }
    MjcfSource composed = files.mjcf;
    composed.xml = ComposeBuiltinCell(files.mjcf.xml, type);
    return CellModel::FromXml(composed, info, X_WR, X_WB);
  }
  if (settings.preset && PresetUrdf(*settings.preset).empty()) {
    // The built-in cell under its preset name.
    const CellModel::RobotInfo info{.name = std::string(PresetInfo(*settings.preset).robot_name),
                                    .source = std::string(NameOf(*settings.preset))};
    return CellModel::FromXml(files.mjcf, info, X_WR, X_WB);
  }
  if (!settings.robot_urdf.empty()) {
    WAAM_DEMAND(files.arm.has_value());
    return UrdfCellModel(*files.arm, files.arm_meshes, settings, X_WR, X_WB);
  }
  CellModel cell(files.mjcf, X_WR, X_WB);
  // A model file of one's own has the positioner its joints describe; a type the scenario names must be that one.
  const planner::PositionerType has = cell.kinematics().positioner.type;
  WAAM_THROW_UNLESS(!settings.positioner_type || *settings.positioner_type == has,
                    settings.where << ": cell.positioner.type is " << NameOf(*settings.positioner_type) << " but "
                                   << cell.file().string() << " has a " << NameOf(has)
                                   << " positioner (its joints pos_tilt, pos_rot)");
  return cell;
}

planner::CellKinematics PartKinematics(const CellModel& cell, const twin::CellSettings& settings) {
  planner::CellKinematics kin = cell.kinematics();
  // The part frame P sits on the plate top (part_origin) with the scenario's offset and turn.
  kin.positioner.X_CP = kin.positioner.X_CP * PlacementPose(settings.part_offset_mm, settings.part_yaw_deg);
  // Accelerations: each axis reaches its rated speed in cell.axis_ramp_s.
  kin.arm.max_accel = kin.arm.max_speed / settings.axis_ramp_s;
  kin.positioner.tilt_max_accel = kin.positioner.tilt_max_speed / settings.axis_ramp_s;
  kin.positioner.rotation_max_accel = kin.positioner.rotation_max_speed / settings.axis_ramp_s;
  return kin;
}


CheckMargins MarginsOf(const CheckReport& report) {
  CheckMargins m;
  m.violations = report.violations.size();
  for (const CheckViolation& v : report.violations) m.violating_samples += static_cast<std::size_t>(v.samples);
  if (report.bounded) m.violating_samples = report.violating_samples_found;
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
