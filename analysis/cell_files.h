// Reading the files a scenario's `cell:` section names (the twin opens none): the built-in cell's or cell.mjcf's
// MJCF with every file it names, or a URDF arm (cell.robot.urdf or a preset's) with its collision meshes.
#pragma once

#include <filesystem>

#include "twin/cell/cell_compose.h"
#include "twin/cell/cell_settings.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::analysis {

// The built-in cell model, DataDir()/twin/data/cell_arcmate100ic.xml.
std::filesystem::path BuiltinCellPath();

// Reads the MJCF file `file` (the built-in cell when empty) and every file it names (<mesh>, <skin>, <hfield>,
// <texture> files and <include>d MJCF, found as MuJoCo 2.2 finds them: absolute, else under the compiler's
// meshdir/texturedir/assetdir, else beside the model). A text that is not XML is returned without assets, for
// MuJoCo to report. Throws InputError naming the file for a missing model, and its line for a file it names that
// is missing or that shares its name (without folders, in any case) with another.
twin::MjcfSource ReadMjcf(const std::filesystem::path& file);

// Reads the URDF `settings.robot_urdf` (refused when a .xacro) and the collision meshes it names: package://NAME/rest
// is DIR/NAME/rest in each of settings.robot_package_paths in turn, then in each ROS_PACKAGE_PATH entry; file://,
// absolute, or relative to the URDF otherwise. Throws InputError naming the URDF and the line of the <mesh> for a
// mesh that is missing, of a format MuJoCo 2.2 does not read (STL and OBJ only), or an ASCII STL, and for a
// package:// URI of an unknown package (naming every directory searched); and as twin::ParseUrdfArm for the URDF.
twin::CellFiles ReadUrdfFiles(const twin::CellSettings& settings);

// Reads what `settings` names for its cell model: the built-in MJCF, a URDF arm or cell.mjcf (ReadMjcf,
// ReadUrdfFiles).
twin::CellFiles ReadCellFiles(const twin::CellSettings& settings);

// The cell model of `settings`: twin::BuildCell over ReadCellFiles(settings). Throws InputError as both do.
twin::CellModel LoadCell(const twin::CellSettings& settings);

// The cell model of the MJCF file `file` (the built-in cell when empty), its bases where the file puts them.
twin::CellModel LoadCellModel(const std::filesystem::path& file);

}  // namespace waam::analysis
