// A whole cell model (MJCF text) around an arm read from URDF: the arm, the torch on its flange, the positioner of
// cell.positioner.type (the built-in cell's two axes, its rotary table alone on a pedestal, or a fixed welding table)
// with plate and clamps, and the floor; and the built-in FANUC cell with another positioner type.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "twin/cell/cell_settings.h"
#include "twin/cell/mujoco_cell.h"
#include "twin/cell/urdf_arm.h"

namespace waam::twin {

// The MJCF of the cell (metres, radians) in the names `waam check` needs (docs/CELL.md). `excluded` lists body pairs
// whose contacts are ignored (arm links whose convex hulls overlap at the zero pose).
std::string ComposeUrdfCell(const UrdfArm& arm, const TorchSettings& torch,
                            const std::vector<std::pair<std::string, std::string>>& excluded,
                            planner::PositionerType type = planner::PositionerType::kTiltRotate);

// The built-in cell (twin/data/cell_arcmate100ic.xml) as MJCF text with its positioner replaced by one of `type`
// (the file itself is the tilt_rotate cell).
std::string ComposeBuiltinCell(planner::PositionerType type);

// The cell of `settings.robot_urdf` with the positioner of settings.positioner_type: the URDF arm with the arm base at X_WR and the positioner base at X_WB (mm).
// Throws InputError for a URDF that cannot be used (see ReadUrdfArm) or a model MuJoCo refuses.
CellModel LoadUrdfCell(const CellSettings& settings, const Eigen::Isometry3d& X_WR, const Eigen::Isometry3d& X_WB);

}  // namespace waam::twin
