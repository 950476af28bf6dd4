// An arm from a URDF (ROS-Industrial support packages): the serial chain base -> flange as MJCF text, with its
// collision geometry, limits and speeds, ready to compose into a cell model. The URDF's text comes parsed here; its
// file and the mesh files it names are read by analysis/cell_files.h.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace waam::twin {

// Which chain of the URDF is the arm (scenario `cell.robot`).
struct UrdfArmOptions {
  std::vector<std::string> joints;  // the six arm joints; empty: the revolute joints root -> flange
  std::string flange;               // the flange link; empty: tool0 if on the chain, else its end
};

// A collision mesh the URDF names.
struct UrdfMesh {
  std::string uri;   // its filename attribute: package://NAME/rest, file://path, absolute or relative to the URDF
  int line = 0;      // the line of its <mesh> element
  std::string file;  // the name of its file in the arm's MJCF (mesh<N> and the URI's extension in lower case): the
                     // key of its bytes among the cell's assets (MjcfSource::assets)
};

// The arm as MJCF fragments (metres, radians). Bodies keep the URDF link names (prefixed `urdf_` where they clash
// with the cell's own names); the six arm joints are named j1..j6; the root link sits in body `robot_base` and the
// flange carries an empty body `link6` (the flange frame F = the URDF flange link), into which the torch goes.
struct UrdfArm {
  std::string name;                        // the URDF's robot name
  std::array<std::string, 6> joint_names;  // the URDF names of j1..j6
  std::string flange_link;                 // the URDF link used as flange
  std::array<double, 6> max_speed_deg_s = {};  // from <limit velocity>, deg/s
  std::string assets_mjcf;                 // <mesh .../> elements, each file named as in `meshes`
  std::string body_mjcf;                   // <body name="robot_base"> ... </body>, "<!--TORCH-->" inside link6
  std::string root_body;                   // the body holding the root link's geoms
  std::vector<UrdfMesh> meshes;            // the collision meshes, in the order of the <mesh .../> elements
  std::string link_without_collision;      // "<file>:<line>: link 'X' has <visual> but no <collision> ..." for the
                                           // first such link (one line), empty when every drawn link collides
};

// Parses the URDF `text` of the file `file` (which names it in messages). Throws InputError naming the file, line
// and element for: text that is not URDF XML or holds xacro elements, no chain of six revolute joints from the
// root to the flange, a `joints` entry or flange the URDF lacks, a revolute joint without <limit>, a continuous
// joint without <limit velocity> or a limit without velocity, a collision geometry other than box, cylinder,
// sphere or mesh.
UrdfArm ParseUrdfArm(const std::string& text, const std::filesystem::path& file, const UrdfArmOptions& options);

}  // namespace waam::twin
