// A whole cell model (MJCF text) around an arm read from URDF: the arm, the torch on its flange, the two-axis
// positioner with plate and clamps of the built-in cell, and the floor.
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
                            const std::vector<std::pair<std::string, std::string>>& excluded);

// The cell of `settings.robot_urdf`: the URDF arm with the arm base at X_WR and the positioner base at X_WB (mm).
// Throws InputError for a URDF that cannot be used (see ReadUrdfArm) or a model MuJoCo refuses.
CellModel LoadUrdfCell(const CellSettings& settings, const Eigen::Isometry3d& X_WR, const Eigen::Isometry3d& X_WB);

}  // namespace waam::twin
