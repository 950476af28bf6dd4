// An arm from a URDF file (ROS-Industrial support packages): the serial chain base -> flange as MJCF text, with its
// collision geometry, limits and speeds, ready to compose into a cell model.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace waam::twin {

// Where the arm comes from (scenario `cell.robot`).
struct UrdfArmOptions {
  std::filesystem::path urdf;                        // the URDF file (a .xacro is refused: run xacro once)
  std::vector<std::filesystem::path> package_paths;  // package://NAME/rest is DIR/NAME/rest in each DIR in turn,
                                                     // then in each ROS_PACKAGE_PATH entry
  std::vector<std::string> joints;                   // the six arm joints; empty: the revolute joints root -> flange
  std::string flange;                                // the flange link; empty: tool0 if on the chain, else its end
};

// The arm as MJCF fragments (metres, radians). Bodies keep the URDF link names (prefixed `urdf_` where they clash
// with the cell's own names); the six arm joints are named j1..j6; the root link sits in body `robot_base` and the
// flange carries an empty body `link6` (the flange frame F = the URDF flange link), into which the torch goes.
struct UrdfArm {
  std::string name;                        // the URDF's robot name
  std::array<std::string, 6> joint_names;  // the URDF names of j1..j6
  std::string flange_link;                 // the URDF link used as flange
  std::array<double, 6> max_speed_deg_s = {};  // from <limit velocity>, deg/s
  std::string assets_mjcf;                 // <mesh .../> elements, absolute file paths
  std::string body_mjcf;                   // <body name="robot_base"> ... </body>, "<!--TORCH-->" inside link6
  std::string root_body;                   // the body holding the root link's geoms
  int mesh_count = 0;                      // collision meshes read
};

// Reads the URDF and resolves its meshes. Throws InputError naming the file, line and element for: a file that is
// not URDF XML or is a .xacro, no chain of six revolute joints from the root to the flange, a `joints` entry or
// flange the URDF lacks, a revolute joint without <limit> or a limit without velocity, a mesh that is missing or
// of a format MuJoCo does not read, a package:// URI of an unknown package (naming every directory searched).
UrdfArm ReadUrdfArm(const UrdfArmOptions& options);

}  // namespace waam::twin
