// The positioner (none, a one-axis turntable or a two-axis tilt/rotate table): the part's pose for given axis angles,
// and the angles that turn a build direction against gravity (dissertation eq. 5.9-5.13 and Appendix B; Lim & Soh
// eq. 1-6).
#pragma once

#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "models/core/enum_names.h"
#include "models/core/numbers.h"

namespace waam::planner {

// cell.positioner.type: which of the two axes (tilt, rotation) the cell has. An axis the cell lacks stays at 0.
enum class PositionerType { kNone, kTurntable, kTiltRotate };
constexpr std::array<EnumName<PositionerType>, 3> EnumNames(PositionerType) {
  return {{{PositionerType::kNone, "none"},
           {PositionerType::kTurntable, "turntable"},
           {PositionerType::kTiltRotate, "tilt_rotate"}}};
}
WAAM_ENUM_JSON(PositionerType)

// True when a cell with a positioner of `type` has the axis (6: tilt, 7: rotation; the arm's 0..5 always).
constexpr bool HasAxis(PositionerType type, int axis) {
  if (axis == 6) return type == PositionerType::kTiltRotate;
  if (axis == 7) return type != PositionerType::kNone;
  return axis >= 0 && axis < 6;
}

// The tilt-rotate positioner's table rotation limit, +-deg (dissertation Table 3): its joint range, and the range of
// the cell's positioner.rotation_deg and of the placement search over it.
inline constexpr double kRotationLimitDeg = 240.0;

// Kinematic chain of the positioner, from its base frame B (on the floor, z up) to the part frame P:
//   X_BP = X_BA * Rx(tilt) * X_AC * Rz(rotation) * X_CP
// where A is the tilt axis frame (tilt about its x) and C the rotating table frame (rotation about its z).
// X_BA and X_AC must be pure translations; X_CP is the part placement on the table (the substrate top, z = 0 of
// P, plus the part's offset and turn on the plate). Lengths in mm, angles in rad. A turntable is the same chain with
// the tilt held at 0 (A is then a fixed frame on the pedestal); no positioner holds both axes at 0 (the plate on a
// fixed table).
struct Positioner {
  PositionerType type = PositionerType::kTiltRotate;
  Eigen::Vector3d p_BA = Eigen::Vector3d(0.0, 0.0, 700.0);   // tilt axis in B, mm
  Eigen::Vector3d p_AC = Eigen::Vector3d(0.0, 0.0, 60.0);    // table (rotation) frame in A at tilt 0, mm
  Eigen::Isometry3d X_CP = Eigen::Isometry3d::Identity();   // part frame on the table, mm
  double tilt_lower = -70.0 * kPi / 180.0;                 // rad (140 deg range, Table 3)
  double tilt_upper = 70.0 * kPi / 180.0;
  double rotation_lower = -kRotationLimitDeg * kPi / 180.0;  // rad (480 deg range, Table 3)
  double rotation_upper = kRotationLimitDeg * kPi / 180.0;
  double tilt_max_speed = 120.0 * kPi / 180.0;             // rad/s (Table 3)
  double rotation_max_speed = 190.0 * kPi / 180.0;         // rad/s (Table 3)
  // rad/s^2: no data-sheet figure; the speed reached in kAxisRampTimeS = 0.25 s (opw_arm.h), as for the arm.
  double tilt_max_accel = 120.0 * kPi / 180.0 / 0.25;
  double rotation_max_accel = 190.0 * kPi / 180.0 / 0.25;
};

// Part pose in the positioner base frame for the two axis angles (rad), mm.
Eigen::Isometry3d PartPose(const Positioner& positioner, double tilt, double rotation);

// Axis angles for one build direction.
struct PositionerAngles {
  double tilt = 0.0;        // rad
  double rotation = 0.0;    // rad
  bool at_limit = false;    // the tilt needed lies outside the tilt range; the tilt is held at its limit
  double residual_rad = 0.0;  // angle left between the turned build direction and vertical (torch tilt), rad
};

// Angles (rad) that turn `build_dir_P` (unit, part frame) to +z of B, choosing among the two solutions and the 2 pi
// copies of the rotation the one nearest `previous` (tilt, rotation). When the build direction is already vertical
// the rotation keeps previous.rotation. Past the tilt range the tilt stays at its limit (the torch then tilts by
// residual_rad to keep the neutral welding position, dissertation section 5.3). A turntable keeps the tilt at 0 and
// the rotation at previous.rotation (turning a tilted build direction about the vertical leaves its angle to
// vertical as it is); its residual is that angle and at_limit says it is not 0. No positioner keeps both at 0.
PositionerAngles SolvePositionerAngles(const Positioner& positioner, const Eigen::Vector3d& build_dir_P,
                                       const PositionerAngles& previous);

// The same with the process's tolerance on the torch angle to gravity: the positioner need not turn the build
// direction exactly up, only to within `tolerance_rad` of it. It keeps the previous rotation while that is possible
// (the tilt alone then brings the direction as close to up as it can) and otherwise turns the table the least angle
// that does: near a vertical build direction the table then stands still instead of spinning round to follow its
// small horizontal part (the rotation speed of the exact solution grows without bound there). Falls back to the exact
// solution where the kept rotation leaves the rotation range or needs a tilt outside the tilt range. tolerance 0:
// SolvePositionerAngles.
PositionerAngles SolvePositionerAnglesWithin(const Positioner& positioner, const Eigen::Vector3d& build_dir_P,
                                             const PositionerAngles& previous, double tolerance_rad);

}  // namespace waam::planner
