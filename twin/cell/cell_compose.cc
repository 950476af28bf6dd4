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

// The positioner of `type` at the world origin (BuildCell places positioner_base), as MJCF in radians or, for the
// built-in file, degrees. tilt_rotate: the built-in cell's (tilt +-70 deg, rotation +-240 deg, dissertation
// Table 3); turntable: its rotary table alone on a fixed pedestal, the plate top at the same 600 mm working height;
// none: a fixed welding table, plate top at 600 mm. Every type carries the same 300 x 300 x 20 mm plate and two
// clamps (bodies substrate and fixture, site part_origin on the plate top).
std::string PositionerMjcf(planner::PositionerType type, bool degrees) {
  auto angle = [degrees](double deg) { return degrees ? deg : Rad(deg); };
  const std::string plate =
      "        <geom name=\"plate\" type=\"box\" pos=\"0 0 0.01\" size=\"0.15 0.15 0.01\" rgba=\"0.6 0.6 0.65 1\"/>\n"
      "        <site name=\"part_origin\" pos=\"0 0 0.02\" size=\"0.005\"/>\n"
      "        <body name=\"fixture\" pos=\"0 0 0.02\">\n"
      "          <geom name=\"clamp_left\" type=\"box\" pos=\"-0.135 0 0.008\" size=\"0.012 0.04 0.008\" "
      "rgba=\"0.8 0.1 0.1 1\"/>\n"
      "          <geom name=\"clamp_right\" type=\"box\" pos=\"0.135 0 0.008\" size=\"0.012 0.04 0.008\" "
      "rgba=\"0.8 0.1 0.1 1\"/>\n"
      "        </body>\n";
  std::ostringstream x;
  x << "<body name=\"positioner_base\" pos=\"1.05 0 0\" quat=\"" << N(std::cos(kPi / 4)) << " 0 0 "
    << N(std::sin(kPi / 4)) << "\">\n";
  if (type == planner::PositionerType::kTiltRotate) {
    x << "  <geom name=\"pedestal\" type=\"box\" pos=\"0 0 0.2\" size=\"0.12 0.1 0.2\" rgba=\"0.2 0.35 0.6 1\"/>\n"
      << "  <body name=\"tilt\" pos=\"0 0 0.5\">\n"
      << "    <inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"0.01 0.01 0.01\"/>\n"
      << "    <joint name=\"pos_tilt\" axis=\"1 0 0\" limited=\"true\" range=\"" << N(angle(-70)) << " "
      << N(angle(70)) << "\"/>\n"
      << "    <geom name=\"tilt_housing\" type=\"box\" pos=\"0 0 0.01\" size=\"0.14 0.12 0.035\" "
         "rgba=\"0.2 0.35 0.6 1\"/>\n"
      << "    <body name=\"table\" pos=\"0 0 0.08\">\n";
  } else if (type == planner::PositionerType::kTurntable) {
    // A rotary table on a column; the table top 580 mm above the floor, the plate top at 600 mm.
    x << "  <geom name=\"pedestal\" type=\"cylinder\" fromto=\"0 0 0 0 0 0.53\" size=\"0.2\" "
         "rgba=\"0.2 0.35 0.6 1\"/>\n"
      << "  <geom name=\"drive_housing\" type=\"cylinder\" fromto=\"0 0 0.53 0 0 0.55\" size=\"0.16\" "
         "rgba=\"0.2 0.35 0.6 1\"/>\n"
      << "    <body name=\"table\" pos=\"0 0 0.58\">\n";
  } else {
    // A welding table: a 600 x 600 x 20 mm top on a central column, the plate top at 600 mm.
    x << "  <geom name=\"table_leg\" type=\"box\" pos=\"0 0 0.28\" size=\"0.1 0.1 0.28\" rgba=\"0.2 0.35 0.6 1\"/>\n"
      << "  <geom name=\"table_top\" type=\"box\" pos=\"0 0 0.57\" size=\"0.3 0.3 0.01\" "
         "rgba=\"0.4 0.4 0.45 1\"/>\n"
      << "      <body name=\"substrate\" pos=\"0 0 0.58\">\n"
      << plate << "      </body>\n</body>\n";
    return x.str();
  }
  x << "      <inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"0.01 0.01 0.01\"/>\n"
    << "      <joint name=\"pos_rot\" axis=\"0 0 1\" limited=\"true\" range=\""
    << N(angle(-planner::kRotationLimitDeg)) << " " << N(angle(planner::kRotationLimitDeg)) << "\"/>\n"
    << "      <geom name=\"table_disk\" type=\"cylinder\" fromto=\"0 0 -0.025 0 0 0\" size=\"0.25\" "
       "rgba=\"0.4 0.4 0.45 1\"/>\n"
    << "      <body name=\"substrate\" pos=\"0 0 0\">\n"
    << plate << "      </body>\n    </body>\n";
  if (type == planner::PositionerType::kTiltRotate) x << "  </body>\n";
  x << "</body>\n";
  return x.str();
}

// The contact exclusions of the positioner of `type` (bodies that touch by construction).
std::string PositionerExcludes(planner::PositionerType type) {
  switch (type) {
    case planner::PositionerType::kTiltRotate:
      return "<exclude body1=\"tilt\" body2=\"substrate\"/>\n"
             "<exclude body1=\"positioner_base\" body2=\"tilt\"/>\n"
             "<exclude body1=\"positioner_base\" body2=\"table\"/>\n";
    case planner::PositionerType::kTurntable:
      return "<exclude body1=\"positioner_base\" body2=\"table\"/>\n"
             "<exclude body1=\"positioner_base\" body2=\"substrate\"/>\n";
    case planner::PositionerType::kNone:
      return "<exclude body1=\"positioner_base\" body2=\"substrate\"/>\n";
  }
  return "";
}

}  // namespace

std::string ComposeUrdfCell(const UrdfArm& arm, const TorchSettings& torch,
                            const std::vector<std::pair<std::string, std::string>>& excluded,
                            planner::PositionerType type) {
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
    << PositionerMjcf(type, false)
    << "</worldbody>\n<contact>\n"
    << "<exclude body1=\"world\" body2=\"robot_base\"/>\n"
    << "<exclude body1=\"world\" body2=\"" << arm.root_body << "\"/>\n"
    << "<exclude body1=\"world\" body2=\"positioner_base\"/>\n"
    << PositionerExcludes(type);
  for (const auto& [a, b] : excluded) x << "<exclude body1=\"" << a << "\" body2=\"" << b << "\"/>\n";
  x << "</contact>\n</mujoco>\n";
  return x.str();
}

std::string ComposeBuiltinCell(const std::string& builtin_xml, planner::PositionerType type) {
  // The file's positioner body (from `<body name="positioner_base"` to its matching `</body>`) is cut out and the
  // composed one put in its place (in degrees, as the file's compiler says); the file's contact exclusions of the
  // positioner's bodies give way to those of the new one. The arm is the file's, untouched.
  std::string xml = builtin_xml;
  const std::size_t start = xml.find("<body name=\"positioner_base\"");
  WAAM_DEMAND(start != std::string::npos);
  std::size_t at = start + 1;
  int depth = 1;
  while (depth > 0) {
    const std::size_t open = xml.find("<body", at);
    const std::size_t close = xml.find("</body>", at);
    WAAM_DEMAND(close != std::string::npos);
    if (open < close) {
      ++depth;
      at = open + 1;
    } else {
      --depth;
      at = close + 1;
    }
  }
  const std::size_t end = at - 1 + std::string("</body>").size();
  xml.replace(start, end - start, PositionerMjcf(type, true));
  std::string out;
  std::istringstream lines(xml);
  for (std::string line; std::getline(lines, line);) {
    const bool positioner_exclude = line.find("<exclude") != std::string::npos &&
                                    (line.find("\"tilt\"") != std::string::npos ||
                                     line.find("\"table\"") != std::string::npos ||
                                     line.find("\"substrate\"") != std::string::npos);
    if (positioner_exclude) continue;
    if (line.find("</contact>") != std::string::npos) out += PositionerExcludes(type);
    out += line + "\n";
  }
  return out;
}

CellModel UrdfCellModel(const UrdfArm& arm, const MjcfSource& meshes, const CellSettings& settings,
                        const Eigen::Isometry3d& X_WR, const Eigen::Isometry3d& X_WB) {
  CellModel::RobotInfo info;
  info.name = settings.preset ? std::string(PresetInfo(*settings.preset).robot_name) : arm.name;
  info.source = settings.preset ? std::string(NameOf(*settings.preset)) : settings.robot_urdf.string();
  info.joints = arm.joint_names;
  info.incomplete_geometry = arm.link_without_collision;
  MjcfSource mjcf = meshes;
  mjcf.file = settings.robot_urdf;
  // Arm links whose collision shapes (convex hulls of the meshes) already touch at the zero pose touch by design:
  // their contacts are excluded, as the built-in cell excludes its base against the first link.
  const planner::PositionerType type = settings.positioner_type.value_or(planner::PositionerType::kTiltRotate);
  mjcf.xml = ComposeUrdfCell(arm, settings.torch, {}, type);
  const CellModel first = CellModel::FromXml(mjcf, info, X_WR, X_WB);
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
  mjcf.xml = ComposeUrdfCell(arm, settings.torch, {excluded.begin(), excluded.end()}, type);
  return CellModel::FromXml(mjcf, info, X_WR, X_WB);
}

}  // namespace waam::twin
