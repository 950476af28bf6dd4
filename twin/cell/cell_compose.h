// A whole cell model (MJCF text) around an arm read from URDF: the arm, the torch on its flange, the positioner of
// cell.positioner.type (the built-in cell's two axes, its rotary table alone on a pedestal, or a fixed welding table)
// with plate and clamps, and the floor; the built-in FANUC cell with another positioner type; and the cell model of
// a scenario's `cell:` section, read (analysis/cell_files.h).
#pragma once

#include <optional>
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

// The built-in cell's MJCF text `builtin_xml` (twin/data/cell_arcmate100ic.xml, the tilt_rotate cell) with its
// positioner replaced by one of `type`.
std::string ComposeBuiltinCell(const std::string& builtin_xml, planner::PositionerType type);

// What a scenario's `cell:` section names, read: the MJCF of the cell (the built-in one or cell.mjcf, with the files
// it names), or the arm of a URDF (cell.robot.urdf or a preset's) with its meshes.
struct CellFiles {
  MjcfSource mjcf;             // the cell's MJCF; unused for a URDF arm
  std::optional<UrdfArm> arm;  // the URDF arm, parsed
  MjcfSource arm_meshes;       // the URDF's file (`file`) and its meshes' bytes by UrdfMesh::file (`assets`)
};

// The cell of `settings.robot_urdf` around `arm` (its meshes in `meshes.assets`, the URDF's path in `meshes.file`)
// with the positioner of settings.positioner_type, the arm base at X_WR and the positioner base at X_WB (mm).
// Throws InputError for a model MuJoCo refuses.
CellModel UrdfCellModel(const UrdfArm& arm, const MjcfSource& meshes, const CellSettings& settings,
                        const Eigen::Isometry3d& X_WR, const Eigen::Isometry3d& X_WB);

}  // namespace waam::twin
