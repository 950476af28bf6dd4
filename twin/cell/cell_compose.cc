// Composes the MJCF of a cell around a URDF arm (see cell_compose.h); the positioner is the built-in one
// (twin/data/cell_arcmate100ic.xml: FANUC 500 kg class two-axis positioner, dissertation Table 3).
#include "twin/cell/cell_compose.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include <Eigen/Geometry>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "twin/cell/cell_presets.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {
namespace {
namespace fs = std::filesystem;

std::string N(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

double Rad(double deg) { return deg * kPi / 180.0; }

// The torch on the flange frame F: straight along the TCP direction, nozzle ending 15 mm (contact tip to work
// distance) above the TCP; the tcp site's z points along the torch into the work, as in the built-in cell.
std::string TorchBody(const TorchSettings& torch) {
  const Eigen::Vector3d tcp(torch.tcp_mm[0], torch.tcp_mm[1], torch.tcp_mm[2]);
  const double L = tcp.norm() / 1000.0;
  const double r = torch.nozzle_radius_mm / 1000.0;
  const double nl = torch.nozzle_length_mm / 1000.0;
  const double nozzle_end = L - 0.015 - r;
  const double nozzle_start = std::max(0.0, nozzle_end - nl);
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), tcp.normalized());
  std::string s = "    <body name=\"torch\" quat=\"" + N(q.w()) + " " + N(q.x()) + " " + N(q.y()) + " " + N(q.z()) +
                  "\">\n";
  if (nozzle_start > 0.03) {
    s += "      <geom name=\"torch_body\" type=\"capsule\" fromto=\"0.03 0 0 " + N(nozzle_start) +
         " 0 0\" size=\"0.022\" rgba=\"0.1 0.1 0.1 1\"/>\n";
  }
  s += "      <geom name=\"nozzle\" type=\"capsule\" fromto=\"" + N(nozzle_start) + " 0 0 " + N(nozzle_end) +
       " 0 0\" size=\"" + N(r) + "\" rgba=\"0.7 0.5 0.3 1\"/>\n";
  s += "      <site name=\"tcp\" pos=\"" + N(L) + " 0 0\" xyaxes=\"0 0 1 0 -1 0\" size=\"0.004\"/>\n";
  return s + "    </body>\n";
}

}  // namespace

std::string ComposeUrdfCell(const UrdfArm& arm, const TorchSettings& torch,
                            const std::vector<std::pair<std::string, std::string>>& excluded) {
  std::string body = arm.body_mjcf;
  const std::string marker = "<!--TORCH-->";
  const std::size_t at = body.find(marker);
  WAAM_DEMAND(at != std::string::npos);
  body.replace(at, marker.size(), TorchBody(torch));

  std::ostringstream x;
  x << "<mujoco model=\"waam_cell_urdf\">\n"
    << "<compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
    << "<custom><numeric name=\"max_speed_deg_s\" data=\"";
  for (double v : arm.max_speed_deg_s) x << N(v) << " ";
  x << "120 190\"/></custom>\n"
    << "<default><geom rgba=\"0.9 0.75 0.1 1\" condim=\"1\"/></default>\n"
    << "<asset>\n" << arm.assets_mjcf << "</asset>\n"
    << "<worldbody>\n"
    << "<geom name=\"floor\" type=\"plane\" size=\"4 4 0.1\" rgba=\"0.5 0.5 0.5 1\"/>\n"
    << body
    // The positioner of the built-in cell: tilt +-70 deg, rotation +-240 deg, 300 x 300 x 20 mm plate, two clamps.
    << "<body name=\"positioner_base\" pos=\"1.05 0 0\" quat=\"" << N(std::cos(kPi / 4)) << " 0 0 "
    << N(std::sin(kPi / 4)) << "\">\n"
    << "  <geom name=\"pedestal\" type=\"box\" pos=\"0 0 0.2\" size=\"0.12 0.1 0.2\" rgba=\"0.2 0.35 0.6 1\"/>\n"
    << "  <body name=\"tilt\" pos=\"0 0 0.5\">\n"
    << "    <inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"0.01 0.01 0.01\"/>\n"
    << "    <joint name=\"pos_tilt\" axis=\"1 0 0\" limited=\"true\" range=\"" << N(-Rad(70)) << " " << N(Rad(70))
    << "\"/>\n"
    << "    <geom name=\"tilt_housing\" type=\"box\" pos=\"0 0 0.01\" size=\"0.14 0.12 0.035\" "
       "rgba=\"0.2 0.35 0.6 1\"/>\n"
    << "    <body name=\"table\" pos=\"0 0 0.08\">\n"
    << "      <inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"0.01 0.01 0.01\"/>\n"
    << "      <joint name=\"pos_rot\" axis=\"0 0 1\" limited=\"true\" range=\"" << N(-Rad(240)) << " "
    << N(Rad(240)) << "\"/>\n"
    << "      <geom name=\"table_disk\" type=\"cylinder\" fromto=\"0 0 -0.025 0 0 0\" size=\"0.25\" "
       "rgba=\"0.4 0.4 0.45 1\"/>\n"
    << "      <body name=\"substrate\" pos=\"0 0 0\">\n"
    << "        <geom name=\"plate\" type=\"box\" pos=\"0 0 0.01\" size=\"0.15 0.15 0.01\" rgba=\"0.6 0.6 0.65 1\"/>\n"
    << "        <site name=\"part_origin\" pos=\"0 0 0.02\" size=\"0.005\"/>\n"
    << "        <body name=\"fixture\" pos=\"0 0 0.02\">\n"
    << "          <geom name=\"clamp_left\" type=\"box\" pos=\"-0.135 0 0.008\" size=\"0.012 0.04 0.008\" "
       "rgba=\"0.8 0.1 0.1 1\"/>\n"
    << "          <geom name=\"clamp_right\" type=\"box\" pos=\"0.135 0 0.008\" size=\"0.012 0.04 0.008\" "
       "rgba=\"0.8 0.1 0.1 1\"/>\n"
    << "        </body>\n      </body>\n    </body>\n  </body>\n</body>\n"
    << "</worldbody>\n<contact>\n"
    << "<exclude body1=\"world\" body2=\"robot_base\"/>\n"
    << "<exclude body1=\"world\" body2=\"" << arm.root_body << "\"/>\n"
    << "<exclude body1=\"world\" body2=\"positioner_base\"/>\n"
    << "<exclude body1=\"tilt\" body2=\"substrate\"/>\n"
    << "<exclude body1=\"positioner_base\" body2=\"tilt\"/>\n"
    << "<exclude body1=\"positioner_base\" body2=\"table\"/>\n";
  for (const auto& [a, b] : excluded) x << "<exclude body1=\"" << a << "\" body2=\"" << b << "\"/>\n";
  x << "</contact>\n</mujoco>\n";
  return x.str();
}

CellModel LoadUrdfCell(const CellSettings& settings, const Eigen::Isometry3d& X_WR, const Eigen::Isometry3d& X_WB) {
  UrdfArmOptions options;
  options.urdf = settings.robot_urdf;
  options.package_paths = settings.robot_package_paths;
  options.joints = settings.robot_joints;
  options.flange = settings.robot_flange;
  const UrdfArm arm = ReadUrdfArm(options);
  CellModel::RobotInfo info;
  info.name = settings.preset ? std::string(PresetInfo(*settings.preset).robot_name) : arm.name;
  info.source = settings.preset ? std::string(NameOf(*settings.preset)) : settings.robot_urdf.string();
  const fs::path file = settings.robot_urdf;
  info.joints = arm.joint_names;
  // Arm links whose collision shapes (convex hulls of the meshes) already touch at the zero pose touch by design:
  // their contacts are excluded, as the built-in cell excludes its base against the first link.
  const CellModel first = CellModel::FromXml(ComposeUrdfCell(arm, settings.torch, {}), info, X_WR, X_WB, file);
  CellState state(first);
  state.SetJoints(planner::Joints8::Zero());
  std::vector<CellContact> contacts;
  state.Collide(0.0, &contacts, nullptr);
  static const std::set<std::string> kCellBodies = {"torch", "link6", "positioner_base", "tilt", "table",
                                                    "substrate", "fixture", "world"};
  std::set<std::pair<std::string, std::string>> excluded;
  for (const CellContact& c : contacts) {
    if (kCellBodies.count(c.body1) || kCellBodies.count(c.body2)) continue;
    excluded.insert(std::minmax(c.body1, c.body2));
  }
  if (excluded.empty()) return first;
  return CellModel::FromXml(ComposeUrdfCell(arm, settings.torch, {excluded.begin(), excluded.end()}), info, X_WR,
                            X_WB, file);
}

}  // namespace waam::twin
