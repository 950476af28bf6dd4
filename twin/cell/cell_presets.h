// The library of cells behind `cell.preset`: one complete cell per name (arm, torch, placement and positioner: the
// built-in cell's two axes, its rotary table alone, or a fixed welding table; each with plate and clamps). The FANUC preset is the built-in MJCF; the others are arms
// we wrote as URDF with primitive collision shapes (twin/data/presets/*.urdf, each citing its kinematics, limits and
// speeds) read through the URDF path (twin/cell/urdf_arm.h, cell_compose.h). The names are the table of CellPreset
// in cell_settings.h, used by the scenario parser, its error message and docs/SCENARIOS.md.
#pragma once

#include <array>
#include <filesystem>
#include <string_view>

#include "planner/program/program_motion.h"
#include "twin/cell/cell_settings.h"

namespace waam::twin {

struct CellPresetInfo {
  CellPreset preset;
  std::string_view robot_name;  // vendor first, as check.json robot.name
  std::string_view urdf;        // file in DataDir()/twin/data/presets; empty: the built-in MJCF
  double reach_mm;              // published reach to the wrist centre, mm
  std::array<double, 3> positioner_base_mm;  // where the preset puts the positioner (arm base at the origin), mm
  TorchSettings torch;          // the torch on the flange (URDF presets; the built-in cell has its own)
  planner::PositionerType positioner = planner::PositionerType::kTiltRotate;  // its positioner's axes
};

// The preset's entry in the library (every CellPreset has one).
const CellPresetInfo& PresetInfo(CellPreset preset);

// The URDF file of a URDF preset (empty path for the built-in one).
std::filesystem::path PresetUrdf(CellPreset preset);

// The program dialect of the preset's controller (fanuc_ls, abb_rapid, kuka_krl, yaskawa_jbi): what `waam export`
// writes when neither --format nor the output file's extension names one.
planner::ProgramFormat PresetDialect(CellPreset preset);

// Sets `cell` to the preset's cell: its arm (robot_urdf) and torch, the arm at the origin facing +x, the positioner
// at the preset's place with its tilt axis across the line between them. The scenario's own keys are read after.
void ApplyPreset(CellPreset preset, CellSettings* cell);

}  // namespace waam::twin
