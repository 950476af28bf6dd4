// The robot cell of a scenario (`cell:` section): where the arm and positioner stand, the part on the plate, and
// the margins `waam check` applies. Every field has a default, so the section is optional.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "models/core/enum_names.h"
#include "planner/kinematics/opw_arm.h"
#include "models/core/field_table.h"
#include "planner/kinematics/positioner.h"

namespace waam::twin {

// cell.positioner.follow
enum class PositionerFollow { kLayer, kPoint };
constexpr std::array<EnumName<PositionerFollow>, 2> EnumNames(PositionerFollow) {
  return {{{PositionerFollow::kLayer, "layer"}, {PositionerFollow::kPoint, "point"}}};
}
WAAM_ENUM_JSON(PositionerFollow)

// cell.resolve: how the axes the weld leaves free (the torch's spin about its axis) are chosen along the path.
enum class CellResolve { kFixed, kOptimise };
constexpr std::array<EnumName<CellResolve>, 2> EnumNames(CellResolve) {
  return {{{CellResolve::kFixed, "fixed"}, {CellResolve::kOptimise, "optimise"}}};
}
WAAM_ENUM_JSON(CellResolve)

// cell.checks.mode: how the check covers the motion between its samples.
enum class CheckMode { kDiscrete, kContinuous };
constexpr std::array<EnumName<CheckMode>, 2> EnumNames(CheckMode) {
  return {{{CheckMode::kDiscrete, "discrete"}, {CheckMode::kContinuous, "continuous"}}};
}
WAAM_ENUM_JSON(CheckMode)

// cell.preset: a complete cell (arm, torch, positioner, plate, clamps, placement); see twin/cell/cell_presets.h.
enum class CellPreset { kFanucArcMate100ic, kAbbIrb1600, kKukaKr16, kYaskawaMh12, kKukaKr16Turntable, kAbbIrb1600Table };
constexpr std::array<EnumName<CellPreset>, 6> EnumNames(CellPreset) {
  return {{{CellPreset::kFanucArcMate100ic, "fanuc_arcmate100ic"},
           {CellPreset::kAbbIrb1600, "abb_irb1600"},
           {CellPreset::kKukaKr16, "kuka_kr16"},
           {CellPreset::kYaskawaMh12, "yaskawa_mh12"},
           {CellPreset::kKukaKr16Turntable, "kuka_kr16_turntable"},
           {CellPreset::kAbbIrb1600Table, "abb_irb1600_table"}}};
}
WAAM_ENUM_JSON(CellPreset)

// cell.torch: the torch on the flange of a URDF arm (the built-in cell has its own).
struct TorchSettings {
  std::array<double, 3> tcp_mm = {0.0, 0.0, 400.0};  // TCP in the flange frame (ROS-Industrial tool0: z out), mm
  double nozzle_radius_mm = 11.0;                     // gas nozzle radius, mm
  double nozzle_length_mm = 74.0;                     // nozzle length (its end 15 mm above the TCP), mm
  // How far the redundancy resolution may turn the torch about its own axis from the default (x away from J1), and
  // the spacing of the values it tries, deg. The weld does not see the turn; the arm's wrist does.
  double spin_range_deg = 90.0;
  double spin_step_deg = 15.0;
  double max_spin_deg_per_mm = 1.0;  // fastest change of the spin along a weld, deg per mm of path
};

struct CellSettings {
  // cell.preset: the cell of a preset (its arm as robot_urdf, or the built-in MJCF for FANUC); the placement and
  // torch keys of the section then override the preset's.
  std::optional<CellPreset> preset;
  // The MuJoCo cell model; empty = the built-in twin/data/cell_arcmate100ic.xml. A user's file must have the
  // joints, bodies and sites listed in docs/SCENARIOS.md ("Describing your own cell").
  std::filesystem::path mjcf;
  // cell.robot.urdf: the arm from a URDF file instead (with the built-in positioner); see twin/cell/urdf_arm.h.
  std::filesystem::path robot_urdf;
  std::vector<std::filesystem::path> robot_package_paths;  // package://NAME/... is DIR/NAME/... in each DIR
  std::vector<std::string> robot_joints;                   // the six arm joints; empty: root -> flange
  std::string robot_flange;                                // the flange link; empty: tool0 or the chain's end
  TorchSettings torch;                                     // cell.torch (URDF arms)
  std::array<double, 3> robot_base_mm = {0.0, 0.0, 0.0};          // arm base frame R in the world, mm
  double robot_yaw_deg = 0.0;                                      // turn of R about world z, deg
  std::array<double, 3> positioner_base_mm = {1050.0, 0.0, 0.0};  // positioner base frame B in the world, mm
  double positioner_yaw_deg = 90.0;                                // turn of B about world z, deg
  // cell.positioner.type: the axes the positioner has (none, turntable, tilt_rotate); unset: the preset's, the
  // model file's (cell.mjcf), else tilt_rotate.
  std::optional<planner::PositionerType> positioner_type;
  double positioner_rotation_deg = 0.0;  // table rotation used while the build direction is vertical, deg
  // layer: angles per layer from its build direction; point: per point from the tool direction (curved layers)
  PositionerFollow positioner_follow = PositionerFollow::kLayer;
  // cell.positioner.tilt_tolerance_deg: the torch angle to gravity the process allows; > 0 lets the positioner stop
  // short of turning the build direction exactly up where that saves table rotation (0: exactly up), deg.
  double positioner_tilt_tolerance_deg = 0.0;
  // cell.resolve: fixed = the torch's x away from J1 everywhere; optimise = the spin per layer that keeps joint and
  // singularity margins and clearances largest (twin/cell/cell_resolve.h), where the fixed rule leaves a violation or
  // a margin short of comfortable (CheckMargin < 1); elsewhere the fixed rule's motion is kept as it is.
  CellResolve resolve = CellResolve::kOptimise;
  std::array<double, 3> part_offset_mm = {0.0, 0.0, 0.0};  // part frame P relative to the plate's top centre, mm
  double part_yaw_deg = 0.0;                               // turn of the part on the plate, deg
  // cell.axis_ramp_s: the time each axis (arm joints and positioner) takes from rest to its rated speed, which gives
  // its acceleration limit for the build's timeline (planner/timeline), s; default planner::kAxisRampTimeS.
  double axis_ramp_s = planner::kAxisRampTimeS;
  double joint_margin_deg = 2.0;         // a joint closer than this to its limit is a violation, deg
  double singularity_deg = 5.0;          // |j5| below this is a wrist-singularity violation, deg
  double step_mm = 1.0;                  // path segments are checked at this spacing, mm
  double collision_tolerance_mm = 0.0;   // contacts penetrating less than this are ignored, mm
  bool part_collision = true;            // check the torch against the layers deposited so far
  // cell.checks.mode: discrete = MuJoCo's collision detection at every sample; continuous = conservative advancement
  // over the joint-space lines between samples as well (twin/cell/cell_sweep.h), with a certified clearance.
  CheckMode check_mode = CheckMode::kDiscrete;
  // Not a scenario key: with optimise, the resolved motion's check is abandoned as soon as its figures prove it worse
  // than the fixed rule's (the fixed rule's is then kept, as the whole check would decide); false checks it whole
  // (`waam place --exhaustive`, tests comparing the two).
  bool prune = true;
  std::string where;                     // "file:line: cell" for messages about the section
};

// The `cell:` section and its sub-sections, one row per key (models/core/field_table.h).
inline constexpr double kCellReachMm = 20000.0;  // any position in the cell, +-mm
inline constexpr std::array kCellFields = {
    OptField<&CellSettings::preset>("preset", "a complete cell (twin/cell/cell_presets.h); absent: none"),
    FileField<&CellSettings::mjcf>("mjcf", "MJCF file", "MuJoCo model of the whole cell; absent = the built-in cell"),
    CustomField<CellSettings>("robot", FieldType::kMap, "the arm (cell.robot)"),
    CustomField<CellSettings>("positioner", FieldType::kMap, "the positioner (cell.positioner)"),
    CustomField<CellSettings>("torch", FieldType::kMap, "the torch of a URDF arm (cell.torch)"),
    OptField<&CellSettings::resolve>("resolve", "how the torch's spin about its axis is chosen along the path"),
    NumField<&CellSettings::axis_ramp_s>("axis_ramp_s", "s", 0.01, 10.0,
                                         "each axis's time from rest to its rated speed (its acceleration limit)"),
    CustomField<CellSettings>("part", FieldType::kMap, "the part on the plate (cell.part)"),
    CustomField<CellSettings>("checks", FieldType::kMap, "the margins of waam check (cell.checks)"),
};
inline constexpr std::array kCellRobotFields = {
    FileField<&CellSettings::robot_urdf>("urdf", "URDF file", "the arm from a URDF file (twin/cell/urdf_arm.h)"),
    FoldersField<&CellSettings::robot_package_paths>("package_paths", "folders: package://NAME/... is DIR/NAME/..."),
    WordsField<&CellSettings::robot_joints>("joints", "joint", 6, "the six arm joints; absent: root to flange"),
    OptField<&CellSettings::robot_flange>("flange", "the flange link; empty: tool0 or the chain's end"),
    NumField<&CellSettings::robot_base_mm>("base_mm", "mm", -kCellReachMm, kCellReachMm, "arm base frame R in the world"),
    NumField<&CellSettings::robot_yaw_deg>("yaw_deg", "deg", -360.0, 360.0, "turn of R about world z"),
};
inline constexpr std::array kCellPositionerFields = {
    OptField<&CellSettings::positioner_type>("type", "the positioner's axes; absent: the preset's or the cell model's"),
    NumField<&CellSettings::positioner_base_mm>("base_mm", "mm", -kCellReachMm, kCellReachMm,
                                           "positioner base frame B in the world"),
    NumField<&CellSettings::positioner_yaw_deg>("yaw_deg", "deg", -360.0, 360.0, "turn of B about world z"),
    NumField<&CellSettings::positioner_rotation_deg>("rotation_deg", "deg", -planner::kRotationLimitDeg,
                                                planner::kRotationLimitDeg,
                                                "table rotation while the build direction is vertical"),
    OptField<&CellSettings::positioner_follow>("follow", "layer: angles per layer; point: per point (curved layers)"),
    NumField<&CellSettings::positioner_tilt_tolerance_deg>("tilt_tolerance_deg", "deg", 0.0, 45.0,
                                                      "torch angle to gravity the process allows"),
};
inline constexpr std::array kTorchFields = {
    NumField<&TorchSettings::tcp_mm>("tcp_mm", "mm", -2000.0, 2000.0, "TCP in the flange frame, at least 50 mm out"),
    NumField<&TorchSettings::nozzle_radius_mm>("nozzle_radius_mm", "mm", 1.0, 50.0, "gas nozzle radius"),
    NumField<&TorchSettings::nozzle_length_mm>("nozzle_length_mm", "mm", 1.0, 500.0, "nozzle length"),
    NumField<&TorchSettings::spin_range_deg>("spin_range_deg", "deg", 0.0, 180.0, "largest turn about the torch axis"),
    NumField<&TorchSettings::spin_step_deg>("spin_step_deg", "deg", 1.0, 90.0, "spacing of the turns tried"),
    NumField<&TorchSettings::max_spin_deg_per_mm>("max_spin_deg_per_mm", "deg/mm", 0.01, 90.0,
                                             "fastest change of the turn along a weld"),
};
inline constexpr std::array kCellPartFields = {
    NumField<&CellSettings::part_offset_mm>("offset_mm", "mm", -kCellReachMm, kCellReachMm,
                                       "part frame P from the plate's top centre"),
    NumField<&CellSettings::part_yaw_deg>("yaw_deg", "deg", -360.0, 360.0, "turn of the part on the plate"),
};
inline constexpr std::array kCellChecksFields = {
    NumField<&CellSettings::joint_margin_deg>("joint_margin_deg", "deg", 0.0, 45.0, "closer to a joint limit: violation"),
    NumField<&CellSettings::singularity_deg>("singularity_deg", "deg", 0.0, 45.0, "j5 closer to 0: wrist singularity"),
    NumField<&CellSettings::step_mm>("step_mm", "mm", 0.1, 100.0, "path segments are checked at this spacing"),
    NumField<&CellSettings::collision_tolerance_mm>("collision_tolerance_mm", "mm", 0.0, 50.0,
                                               "contacts penetrating less are ignored"),
    OptField<&CellSettings::part_collision>("part_collision", "check the torch against the layers deposited so far"),
    OptField<&CellSettings::check_mode>("mode", "discrete: collisions at the samples; continuous: between them too"),
};

// Throws InputError "cell.<sub>.<key> = value: must be in [min, max]" for a number of `cell` outside the range its
// scenario key allows (settings built in code: a placement search, a sweep, an API).
void ValidateCellSettings(const CellSettings& cell);

}  // namespace waam::twin
