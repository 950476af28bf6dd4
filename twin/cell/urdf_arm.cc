// URDF parser for arms: links, joints, collision geometry and the meshes it names, written out as MJCF text.
//
// Why not MuJoCo's own URDF import (mj_loadXML on the .urdf): MuJoCo 2.2 strips every mesh path to its file name and
// looks it up in one mesh directory (package:// URIs and meshes/collision vs meshes/visual are lost), merges bodies
// joined by fixed joints into their parents (tool0 and flange disappear), and cannot attach a second model (the
// torch, positioner, plate and clamps) to the one it imported. Writing the chain as MJCF ourselves is less code than
// working round all three, and keeps every URDF link as a body of the same name.
#include "twin/cell/urdf_arm.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <system_error>

#include <Eigen/Geometry>
#include <tinyxml2.h>

#include "models/core/error.h"
#include "models/core/numbers.h"

namespace waam::twin {
namespace {

constexpr std::size_t kMaxLinks = 1000;  // more links than any arm has; bounds the recursion depth

struct UrdfJoint {
  std::string name, type, parent, child;
  int line = 0;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero(), rpy = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  bool has_limit = false, has_velocity = false;
  double lower = 0.0, upper = 0.0, velocity = 0.0;
};

struct UrdfLink {
  std::string name;
  int line = 0;
  const tinyxml2::XMLElement* element = nullptr;
};

std::string Num(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// URDF rpy: fixed-axis roll, pitch, yaw = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Quaterniond RpyQuat(const Eigen::Vector3d& rpy) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()));
}

std::string PosQuat(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  const Eigen::Quaterniond q = RpyQuat(rpy);
  return " pos=\"" + Num(xyz.x()) + " " + Num(xyz.y()) + " " + Num(xyz.z()) + "\" quat=\"" + Num(q.w()) + " " +
         Num(q.x()) + " " + Num(q.y()) + " " + Num(q.z()) + "\"";
}

class UrdfReader {
 public:
  UrdfReader(const std::filesystem::path& file, const UrdfArmOptions& options)
      : options_(options), file_(file.string()) {}

  UrdfArm Read(const std::string& text) {
    const tinyxml2::XMLError err = doc_.Parse(text.data(), text.size());
    WAAM_THROW_UNLESS(err == tinyxml2::XML_SUCCESS,
                      file_ << ":" << doc_.ErrorLineNum() << ": not a readable XML file: " << doc_.ErrorStr());
    const tinyxml2::XMLElement* robot = doc_.RootElement();
    WAAM_THROW_UNLESS(robot && std::string(robot->Name()) == "robot",
                      file_ << ":" << (robot ? robot->GetLineNum() : 1) << ": the root element must be <robot>");
    for (const tinyxml2::XMLElement* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
      const std::string tag = e->Name();
      WAAM_THROW_UNLESS(tag.rfind("xacro:", 0) != 0,
                        Where(e) << "<" << tag << "> is xacro: run xacro once and name the .urdf it writes");
      if (tag == "link") ReadLink(e);
      if (tag == "joint") ReadJoint(e);
    }
    arm_.name = Attr(robot, "name", false);
    FindChain();
    arm_.root_body = BodyName(root_);
    arm_.body_mjcf = "<body name=\"robot_base\">\n" + Body(root_, "") + "</body>\n";
    return arm_;
  }

 private:
  std::string Where(const tinyxml2::XMLElement* e) const {
    return file_ + ":" + std::to_string(e->GetLineNum()) + ": ";
  }
  std::string Attr(const tinyxml2::XMLElement* e, const char* name, bool required) const {
    const char* v = e->Attribute(name);
    WAAM_THROW_UNLESS(v || !required, Where(e) << "<" << e->Name() << "> lacks attribute '" << name << "'");
    return v ? v : "";
  }
  std::vector<double> Numbers(const tinyxml2::XMLElement* e, const char* name, std::size_t n,
                              std::vector<double> fallback) const {
    const char* v = e->Attribute(name);
    if (!v) return fallback;
    std::istringstream in(v);
    std::vector<double> out;
    double x;
    while (in >> x) out.push_back(x);
    WAAM_THROW_UNLESS(in.eof() && out.size() == n && std::all_of(out.begin(), out.end(), [](double d) {
                        return std::isfinite(d);
                      }),
                      Where(e) << "<" << e->Name() << " " << name << "=\"" << v << "\">: expected " << n
                               << " numbers");
    return out;
  }
  double Number(const tinyxml2::XMLElement* e, const char* name) const {
    const char* v = e->Attribute(name);
    WAAM_THROW_UNLESS(v, Where(e) << "<" << e->Name() << "> lacks attribute '" << name << "'");
    return Numbers(e, name, 1, {})[0];
  }
  void Origin(const tinyxml2::XMLElement* e, Eigen::Vector3d* xyz, Eigen::Vector3d* rpy) const {
    const tinyxml2::XMLElement* o = e->FirstChildElement("origin");
    xyz->setZero();
    rpy->setZero();
    if (!o) return;
    const std::vector<double> p = Numbers(o, "xyz", 3, {0, 0, 0}), r = Numbers(o, "rpy", 3, {0, 0, 0});
    *xyz = Eigen::Vector3d(p[0], p[1], p[2]);
    *rpy = Eigen::Vector3d(r[0], r[1], r[2]);
  }

  void ReadLink(const tinyxml2::XMLElement* e) {
    UrdfLink link;
    link.name = Attr(e, "name", true);
    link.line = e->GetLineNum();
    link.element = e;
    WAAM_THROW_UNLESS(links_.emplace(link.name, link).second, Where(e) << "link '" << link.name << "' defined twice");
  }

  void ReadJoint(const tinyxml2::XMLElement* e) {
    UrdfJoint j;
    j.name = Attr(e, "name", true);
    j.type = Attr(e, "type", true);
    j.line = e->GetLineNum();
    const tinyxml2::XMLElement* parent = e->FirstChildElement("parent");
    const tinyxml2::XMLElement* child = e->FirstChildElement("child");
    WAAM_THROW_UNLESS(parent && child, Where(e) << "joint '" << j.name << "' lacks <parent> or <child>");
    j.parent = Attr(parent, "link", true);
    j.child = Attr(child, "link", true);
    Origin(e, &j.xyz, &j.rpy);
    if (const tinyxml2::XMLElement* axis = e->FirstChildElement("axis")) {
      const std::vector<double> a = Numbers(axis, "xyz", 3, {1, 0, 0});
      j.axis = Eigen::Vector3d(a[0], a[1], a[2]);
      WAAM_THROW_UNLESS(j.axis.norm() > 1e-9, Where(axis) << "joint '" << j.name << "': zero axis");
      j.axis.normalize();
    }
    if (const tinyxml2::XMLElement* limit = e->FirstChildElement("limit")) {
      j.has_limit = true;
      j.lower = limit->Attribute("lower") ? Number(limit, "lower") : 0.0;
      j.upper = limit->Attribute("upper") ? Number(limit, "upper") : 0.0;
      j.has_velocity = limit->Attribute("velocity") != nullptr;
      WAAM_THROW_UNLESS(j.has_velocity, Where(limit) << "joint '" << j.name
                                                     << "': <limit> without velocity (rad/s; waam checks joint speeds)");
      j.velocity = Number(limit, "velocity");
      WAAM_THROW_UNLESS(j.velocity > 0.0, Where(limit) << "joint '" << j.name << "': velocity must be > 0");
    }
    WAAM_THROW_UNLESS(children_of_.count(j.child) == 0 && parent_joint_.count(j.child) == 0,
                      Where(e) << "link '" << j.child << "' has two parent joints");
    parent_joint_[j.child] = joints_.size();
    joints_.push_back(j);
  }

  void FindChain() {
    const tinyxml2::XMLElement* robot = doc_.RootElement();
    FindTree(robot);
    const std::vector<std::size_t> named = NamedJoints(robot);
    const std::string flange = PickFlange(named);
    WAAM_THROW_UNLESS(links_.count(flange), Where(robot) << "the URDF has no link '" << flange
                                                         << "' to use as flange (cell.robot.flange)");
    const std::vector<std::size_t> moving = MovingJoints(robot, flange);
    if (!named.empty()) {
      WAAM_THROW_UNLESS(named.size() == 6 && named == moving,
                        Where(robot) << "cell.robot.joints must be the six revolute joints from '" << root_
                                     << "' to '" << flange << "' in order");
    }
    for (int k = 0; k < 6; ++k) TakeArmJoint(k, moving[k]);
    flange_ = flange;
    arm_.flange_link = flange;
  }

  // The joints' parent-child map and the root: the links must form one tree with one root, small enough to recurse
  // through.
  void FindTree(const tinyxml2::XMLElement* robot) {
    WAAM_THROW_UNLESS(!links_.empty(), Where(robot) << "the URDF has no <link>");
    for (const UrdfJoint& j : joints_) {
      WAAM_THROW_UNLESS(links_.count(j.parent) && links_.count(j.child),
                        file_ << ":" << j.line << ": joint '" << j.name << "' names a link the URDF lacks");
      children_of_[j.parent].push_back(&j - joints_.data());
    }
    // The root: the one link without a parent joint.
    std::vector<std::string> roots;
    for (const auto& [name, link] : links_) {
      if (!parent_joint_.count(name)) roots.push_back(name);
    }
    WAAM_THROW_UNLESS(roots.size() == 1, Where(robot) << "the URDF must be one tree of links with one root, has "
                                                      << roots.size() << " roots");
    root_ = roots[0];
    // Every link must hang below the root (no cycles).
    WAAM_THROW_UNLESS(links_.size() <= kMaxLinks, Where(robot) << "the URDF has " << links_.size()
                                                               << " links, more than the limit of " << kMaxLinks);
    std::vector<std::string> stack = {root_};
    std::size_t reached = 0;
    while (!stack.empty()) {
      const std::string link = stack.back();
      stack.pop_back();
      ++reached;
      if (children_of_.count(link)) {
        for (std::size_t ji : children_of_.at(link)) stack.push_back(joints_[ji].child);
      }
    }
    WAAM_THROW_UNLESS(reached == links_.size(), Where(robot) << "the links do not form one tree below '" << root_
                                                             << "' (a cycle of joints)");
  }

  // The joints from the root down to `link`.
  std::vector<std::size_t> PathTo(const std::string& link) const {
    std::vector<std::size_t> path;
    for (std::string l = link; parent_joint_.count(l); l = joints_[parent_joint_.at(l)].parent) {
      path.insert(path.begin(), parent_joint_.at(l));
    }
    return path;
  }

  // The indices of the joints cell.robot.joints names, which must exist.
  std::vector<std::size_t> NamedJoints(const tinyxml2::XMLElement* robot) const {
    std::vector<std::size_t> named;
    for (const std::string& name : options_.joints) {
      std::size_t found = joints_.size();
      for (std::size_t i = 0; i < joints_.size(); ++i) {
        if (joints_[i].name == name) found = i;
      }
      WAAM_THROW_UNLESS(found < joints_.size(), Where(robot) << "cell.robot.joints names joint '" << name
                                                             << "', which the URDF lacks");
      named.push_back(found);
    }
    return named;
  }

  // The flange: named, else tool0 when it exists, else the deepest link (below the last named joint, if any).
  std::string PickFlange(const std::vector<std::size_t>& named) const {
    std::string flange = options_.flange;
    if (flange.empty() && links_.count("tool0")) flange = "tool0";
    if (flange.empty()) {
      std::size_t best = 0;
      for (const auto& [name, link] : links_) {
        const std::vector<std::size_t> path = PathTo(name);
        if (!named.empty() && std::find(path.begin(), path.end(), named.back()) == path.end()) continue;
        if (flange.empty() || path.size() > best) flange = name, best = path.size();
      }
    }
    return flange;
  }

  // The non-fixed joints from the root to the flange: six revolute (or continuous) joints.
  std::vector<std::size_t> MovingJoints(const tinyxml2::XMLElement* robot, const std::string& flange) const {
    std::vector<std::size_t> moving;
    for (std::size_t i : PathTo(flange)) {
      const UrdfJoint& j = joints_[i];
      if (j.type == "fixed") continue;
      WAAM_THROW_UNLESS(j.type == "revolute" || j.type == "continuous",
                        file_ << ":" << j.line << ": joint '" << j.name << "' is " << j.type
                              << ": the arm must be a serial chain of six revolute joints from '" << root_ << "' to '"
                              << flange << "'");
      moving.push_back(i);
    }
    WAAM_THROW_UNLESS(moving.size() == 6, Where(robot) << "the chain from '" << root_ << "' to '" << flange
                                                       << "' has " << moving.size()
                                                       << " revolute joints: the arm must be a serial chain of six");
    return moving;
  }

  // Joint `ji` as the arm's joint k: its limits and speed must be stated.
  void TakeArmJoint(int k, std::size_t ji) {
    const UrdfJoint& j = joints_[ji];
    WAAM_THROW_UNLESS(j.type == "continuous" || j.has_limit,
                      file_ << ":" << j.line << ": joint '" << j.name << "' lacks <limit> (lower, upper, velocity)");
    WAAM_THROW_UNLESS(j.has_velocity || j.type != "continuous",
                      file_ << ":" << j.line << ": joint '" << j.name
                            << "' is continuous without <limit velocity>: no bound on its speed (rad/s; waam checks "
                               "joint speeds and bounds the motion between samples by them)");
    WAAM_THROW_UNLESS(j.has_velocity, file_ << ":" << j.line << ": joint '" << j.name
                                            << "' lacks <limit velocity> (rad/s; waam checks joint speeds)");
    WAAM_THROW_UNLESS(j.type == "continuous" || j.lower < j.upper,
                      file_ << ":" << j.line << ": joint '" << j.name << "': limit lower must be < upper");
    arm_.joint_names[k] = j.name;
    arm_.max_speed_deg_s[k] = j.velocity * 180.0 / kPi;
    arm_index_[ji] = k;
  }

  // <geom> elements of a link's <collision> children.
  std::string Geoms(const UrdfLink& link) {
    std::string out;
    int n = 0;
    for (const tinyxml2::XMLElement* c = link.element->FirstChildElement("collision"); c;
         c = c->NextSiblingElement("collision")) {
      Eigen::Vector3d xyz, rpy;
      Origin(c, &xyz, &rpy);
      const tinyxml2::XMLElement* g = c->FirstChildElement("geometry");
      WAAM_THROW_UNLESS(g && g->FirstChildElement(), Where(c) << "<collision> of link '" << link.name
                                                              << "' lacks <geometry>");
      const tinyxml2::XMLElement* shape = g->FirstChildElement();
      const std::string type = shape->Name();
      std::string geom = "  <geom name=\"" + link.name + "_collision" + std::to_string(n++) + "\"" + PosQuat(xyz, rpy);
      if (type == "box") {
        const std::vector<double> s = Numbers(shape, "size", 3, {});
        WAAM_THROW_UNLESS(shape->Attribute("size"), Where(shape) << "<box> lacks attribute 'size'");
        geom += " type=\"box\" size=\"" + Num(s[0] / 2) + " " + Num(s[1] / 2) + " " + Num(s[2] / 2) + "\"";
      } else if (type == "cylinder") {
        geom += " type=\"cylinder\" size=\"" + Num(Number(shape, "radius")) + " " + Num(Number(shape, "length") / 2) +
                "\"";
      } else if (type == "sphere") {
        geom += " type=\"sphere\" size=\"" + Num(Number(shape, "radius")) + "\"";
      } else if (type == "mesh") {
        // The file is found and read by analysis/cell_files.cc; here it gets its name among the cell's assets.
        UrdfMesh mesh;
        mesh.uri = Attr(shape, "filename", true);
        mesh.line = shape->GetLineNum();
        const std::size_t slash = mesh.uri.find_last_of('/');
        const std::size_t dot = mesh.uri.find_last_of('.');
        std::string ext = dot != std::string::npos && (slash == std::string::npos || dot > slash) ? mesh.uri.substr(dot)
                                                                                                 : "";
        for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        const std::string name = "mesh" + std::to_string(arm_.meshes.size());
        mesh.file = name + ext;
        const std::vector<double> s = Numbers(shape, "scale", 3, {1, 1, 1});
        arm_.assets_mjcf += "<mesh name=\"" + name + "\" file=\"" + mesh.file + "\" scale=\"" + Num(s[0]) + " " +
                            Num(s[1]) + " " + Num(s[2]) + "\"/>\n";
        geom += " type=\"mesh\" mesh=\"" + name + "\"";
        arm_.meshes.push_back(mesh);
      } else {
        WAAM_THROW(Where(shape) << "unknown collision geometry <" << type << "> (box, cylinder, sphere or mesh)");
      }
      out += geom + "/>\n";
    }
    // A link drawn (<visual>) but without <collision> is a body no check can see; the first such link is reported.
    if (n == 0 && link.element->FirstChildElement("visual") && arm_.link_without_collision.empty()) {
      arm_.link_without_collision = file_ + ":" + std::to_string(link.line) + ": link '" + link.name +
                                    "' has <visual> but no <collision> geometry: no collision check sees it";
    }
    return out;
  }

  std::string BodyName(const std::string& link) const {
    static const std::set<std::string> kReserved = {"world",  "robot_base", "link6",     "torch",   "positioner_base",
                                                    "tilt",   "table",      "substrate", "fixture"};
    return kReserved.count(link) ? "urdf_" + link : link;
  }

  // MJCF of a link and everything below it; `placement` the pos/quat of the joint origin.
  std::string Body(const std::string& link_name, const std::string& placement) {
    const UrdfLink& link = links_.at(link_name);
    std::string out = "<body name=\"" + BodyName(link_name) + "\"" + placement + ">\n";
    out += "  <inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"0.01 0.01 0.01\"/>\n";
    if (parent_joint_.count(link_name)) {
      const std::size_t ji = parent_joint_.at(link_name);
      const auto k = arm_index_.find(ji);
      if (k != arm_index_.end()) {
        const UrdfJoint& j = joints_[ji];
        const double lo = j.type == "continuous" ? -2 * kPi : j.lower;
        const double hi = j.type == "continuous" ? 2 * kPi : j.upper;
        out += "  <joint name=\"j" + std::to_string(k->second + 1) + "\" type=\"hinge\" axis=\"" + Num(j.axis.x()) +
               " " + Num(j.axis.y()) + " " + Num(j.axis.z()) + "\" limited=\"true\" range=\"" + Num(lo) + " " +
               Num(hi) + "\"/>\n";
      }
      // Joints off the arm chain (grippers, external axes in the URDF) stay at their zero.
    }
    out += Geoms(link);
    if (link_name == flange_) out += "  <body name=\"link6\">\n<!--TORCH-->\n  </body>\n";
    if (children_of_.count(link_name)) {
      for (std::size_t ji : children_of_.at(link_name)) {
        const UrdfJoint& j = joints_[ji];
        out += Body(j.child, PosQuat(j.xyz, j.rpy));
      }
    }
    return out + "</body>\n";
  }

  const UrdfArmOptions& options_;
  std::string file_;
  tinyxml2::XMLDocument doc_;
  std::map<std::string, UrdfLink> links_;
  std::vector<UrdfJoint> joints_;
  std::map<std::string, std::size_t> parent_joint_;
  std::map<std::string, std::vector<std::size_t>> children_of_;
  std::map<std::size_t, int> arm_index_;
  std::string root_, flange_;
  UrdfArm arm_;
};

}  // namespace

UrdfArm ParseUrdfArm(const std::string& text, const std::filesystem::path& file, const UrdfArmOptions& options) {
  UrdfReader reader(file, options);
  return reader.Read(text);
}

}  // namespace waam::twin
