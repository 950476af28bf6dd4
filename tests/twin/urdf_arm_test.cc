// Tests of arms read from URDF: a KUKA-convention arm in a ROS-Industrial package layout (package:// meshes written
// by the test) loads, is recognised as OPW with the published parameters, agrees with the same arm written as MJCF,
// checks a wall end to end; bad URDFs give one line naming the file and element.
#include "twin/cell/urdf_arm.h"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/cell_files.h"
#include "models/core/error.h"
#include "models/core/numbers.h"
#include "tests/twin/test_plans.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {
namespace {
using analysis::LoadCell;
namespace fs = std::filesystem;
using ::testing::HasSubstr;

// A binary STL box centred at c with half sizes h (metres), as CAD exporters write them.
void WriteBoxStl(const fs::path& file, const Eigen::Vector3d& c, const Eigen::Vector3d& h) {
  std::ofstream out(file, std::ios::binary);
  const char header[80] = "waam test box";
  out.write(header, 80);
  const std::uint32_t n = 12;
  out.write(reinterpret_cast<const char*>(&n), 4);
  auto corner = [&](int i) {
    return Eigen::Vector3f(c.x() + ((i & 1) ? h.x() : -h.x()), c.y() + ((i & 2) ? h.y() : -h.y()),
                           c.z() + ((i & 4) ? h.z() : -h.z()));
  };
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                            {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& f : faces) {
    const Eigen::Vector3f a = corner(f[0]), b = corner(f[1]), d = corner(f[2]);
    const Eigen::Vector3f nrm = (b - a).cross(d - a).normalized();
    for (const Eigen::Vector3f& v : {nrm, a, b, d}) out.write(reinterpret_cast<const char*>(v.data()), 12);
    const std::uint16_t attr = 0;
    out.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

// KUKA KR 16-2 geometry (kuka_kr16_support/config/opw_parameters_kr16_2.yaml: a1 0.26, a2 0.035, c1 0.675,
// c2 0.68, c3 0.67, c4 0.158 m) in KUKA's joint convention as the ROS-Industrial xacros draw it: A1 about -z, A2 and
// A3 about +y with the arm stretched forward at zero, A4 and A6 about -x, A5 about +y, tool0 with z out of the flange.
struct Joint {
  const char* name;
  const char* parent;
  const char* child;
  Eigen::Vector3d xyz;
  Eigen::Vector3d axis;
  double lower_deg, upper_deg, velocity_deg_s;
};
const Joint kJoints[6] = {
    {"joint_a1", "base_link", "link_1", {0, 0, 0.4}, {0, 0, -1}, -185, 185, 156},
    {"joint_a2", "link_1", "link_2", {0.26, 0, 0.275}, {0, 1, 0}, -155, 35, 156},
    {"joint_a3", "link_2", "link_3", {0.68, 0, 0}, {0, 1, 0}, -130, 154, 156},
    {"joint_a4", "link_3", "link_4", {0.3, 0, -0.035}, {-1, 0, 0}, -350, 350, 330},
    {"joint_a5", "link_4", "link_5", {0.37, 0, 0}, {0, 1, 0}, -130, 130, 330},
    {"joint_a6", "link_5", "link_6", {0.158, 0, 0}, {-1, 0, 0}, -350, 350, 615},
};

class UrdfArmTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("waam_urdf_test_" + std::to_string(::getpid()));
    pkg_ = dir_ / "pkgs" / "waam_kr16_support";
    fs::create_directories(pkg_ / "urdf");
    fs::create_directories(pkg_ / "meshes" / "kr16" / "collision");
    for (int i = 1; i <= 6; ++i) {
      // A slim box along each link (from its joint towards the next), inside the link's envelope.
      const Eigen::Vector3d next = i < 6 ? kJoints[i].xyz : Eigen::Vector3d(0.03, 0, 0);
      WriteBoxStl(pkg_ / "meshes" / "kr16" / "collision" / ("link_" + std::to_string(i) + ".stl"), 0.5 * next,
                  (0.5 * next.cwiseAbs()).cwiseMax(Eigen::Vector3d::Constant(0.02)) * 0.6);
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The URDF text; `mutate` may edit it for the bad-input tests.
  std::string Urdf() const {
    std::string s = "<?xml version=\"1.0\"?>\n<robot name=\"KUKA KR 16-2\">\n";
    s += "  <link name=\"base_link\">\n    <collision>\n      <origin xyz=\"0 0 0.1\" rpy=\"0 0 0\"/>\n"
         "      <geometry><cylinder radius=\"0.15\" length=\"0.2\"/></geometry>\n    </collision>\n  </link>\n";
    for (int i = 1; i <= 6; ++i) {
      s += "  <link name=\"link_" + std::to_string(i) + "\">\n    <collision>\n      <origin xyz=\"0 0 0\" rpy=\"0 0 0\"/>\n"
           "      <geometry><mesh filename=\"package://waam_kr16_support/meshes/kr16/collision/link_" +
           std::to_string(i) + ".stl\"/></geometry>\n    </collision>\n  </link>\n";
    }
    s += "  <link name=\"tool0\"/>\n  <link name=\"base\"/>\n";
    for (const Joint& j : kJoints) {
      std::ostringstream o;
      o.precision(17);
      o << "  <joint name=\"" << j.name << "\" type=\"revolute\">\n    <origin xyz=\"" << j.xyz.x() << " " << j.xyz.y()
        << " " << j.xyz.z() << "\" rpy=\"0 0 0\"/>\n    <parent link=\"" << j.parent << "\"/>\n    <child link=\""
        << j.child << "\"/>\n    <axis xyz=\"" << j.axis.x() << " " << j.axis.y() << " " << j.axis.z()
        << "\"/>\n    <limit effort=\"0\" lower=\"" << j.lower_deg * kPi / 180 << "\" upper=\""
        << j.upper_deg * kPi / 180 << "\" velocity=\"" << j.velocity_deg_s * kPi / 180 << "\"/>\n  </joint>\n";
      s += o.str();
    }
    s += "  <joint name=\"base_link-base\" type=\"fixed\">\n    <origin xyz=\"0 0 0.675\" rpy=\"0 0 0\"/>\n"
         "    <parent link=\"base_link\"/>\n    <child link=\"base\"/>\n  </joint>\n";
    s += "  <joint name=\"link_6-tool0\" type=\"fixed\">\n    <origin xyz=\"0 0 0\" rpy=\"0 1.5707963267948966 0\"/>\n"
         "    <parent link=\"link_6\"/>\n    <child link=\"tool0\"/>\n  </joint>\n";
    return s + "</robot>\n";
  }

  fs::path WriteUrdf(const std::string& text) const {
    const fs::path file = pkg_ / "urdf" / "kr16_2.urdf";
    std::ofstream(file) << text;
    return file;
  }

  CellSettings Settings(const fs::path& urdf) const {
    CellSettings s;
    s.robot_urdf = urdf;
    s.robot_package_paths = {dir_ / "pkgs"};
    return s;
  }

  std::string ErrorOf(const CellSettings& settings) const {
    try {
      LoadCell(settings);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }

  // The same arm as MJCF: the built-in cell with its arm replaced by these bodies (link6 = tool0).
  fs::path WriteMjcfTwin() const {
    std::ifstream in(analysis::BuiltinCellPath());
    std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t a = xml.find("<body name=\"robot_base\"");
    const std::size_t b = xml.find("<body name=\"positioner_base\"");
    std::ostringstream arm;
    arm.precision(17);
    arm << "<body name=\"robot_base\" pos=\"0 0 0\">\n";
    for (int i = 0; i < 6; ++i) {
      const Joint& j = kJoints[i];
      arm << "<body name=\"" << (i < 5 ? "link" : "wrist") << i + 1 << "\" pos=\"" << j.xyz.x() << " " << j.xyz.y() << " " << j.xyz.z()
          << "\"><joint name=\"j" << i + 1 << "\" axis=\"" << j.axis.x() << " " << j.axis.y() << " " << j.axis.z()
          << "\" range=\"" << j.lower_deg << " " << j.upper_deg << "\"/><geom type=\"sphere\" size=\"0.01\"/>\n";
    }
    arm << "<body name=\"link6\" euler=\"0 90 0\"><geom type=\"sphere\" size=\"0.01\"/><body name=\"torch\">"
           "<geom name=\"nozzle\" type=\"capsule\" fromto=\"0 0 0.3 0 0 0.374\" size=\"0.011\"/>"
           "<site name=\"tcp\" pos=\"0 0 0.4\"/></body></body>\n";
    for (int i = 0; i < 7; ++i) arm << "</body>\n";
    xml.replace(a, b - a, arm.str());
    const fs::path file = dir_ / "kr16_twin.xml";
    std::ofstream(file) << xml;
    return file;
  }

  fs::path dir_, pkg_;
};

double PoseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm() + 1000.0 * (a.linear() - b.linear()).norm();
}

TEST_F(UrdfArmTest, RosIndustrialPackageLoadsAsAClosedFormArmWithThePublishedParameters) {
  const CellModel cell = LoadCell(Settings(WriteUrdf(Urdf())));
  EXPECT_TRUE(cell.closed_form()) << cell.not_closed_form_reason();
  EXPECT_EQ(cell.robot().name, "KUKA KR 16-2");
  EXPECT_EQ(cell.robot().joints[0], "joint_a1");
  EXPECT_EQ(cell.robot().joints[5], "joint_a6");
  const planner::OpwArm arm = cell.kinematics().arm;
  // opw_parameters_kr16_2.yaml: a1 0.260, a2 0.035, b 0, c1 0.675, c2 0.680, c3 0.670, c4 0.158 m,
  // sign corrections [-1, 1, 1, -1, 1, -1].
  EXPECT_NEAR(arm.a1, 260.0, 1e-9);
  EXPECT_NEAR(arm.a2, 35.0, 1e-9);
  EXPECT_NEAR(arm.b, 0.0, 1e-9);
  EXPECT_NEAR(arm.c1, 675.0, 1e-9);
  EXPECT_NEAR(arm.c2, 680.0, 1e-9);
  EXPECT_NEAR(arm.c3, 670.0, 1e-9);
  EXPECT_NEAR(arm.c4, 158.0, 1e-9);
  const std::array<int, 6> kuka_signs = {-1, 1, 1, -1, 1, -1};
  EXPECT_EQ(arm.sign_corrections, kuka_signs);
  EXPECT_NEAR(arm.max_speed[5], 615.0 * kPi / 180, 1e-9);
  EXPECT_NEAR(arm.upper[3], 350.0 * kPi / 180, 1e-9);
}

TEST_F(UrdfArmTest, ForwardKinematicsAgreeWithTheSameArmWrittenAsMjcf) {
  const CellModel urdf = LoadCell(Settings(WriteUrdf(Urdf())));
  const CellModel mjcf = analysis::LoadCellModel(WriteMjcfTwin());
  EXPECT_TRUE(mjcf.closed_form()) << mjcf.not_closed_form_reason();
  CellState a(urdf), b(mjcf);
  const Eigen::Isometry3d T_a = urdf.kinematics().X_FT.inverse(), T_b = mjcf.kinematics().X_FT.inverse();
  std::mt19937_64 rng(5);
  const planner::OpwArm arm = urdf.kinematics().arm;
  double worst = 0.0;
  for (int trial = 0; trial < 1000; ++trial) {
    planner::Joints8 q = planner::Joints8::Zero();
    for (int j = 0; j < 6; ++j) q[j] = std::uniform_real_distribution<double>(arm.lower[j], arm.upper[j])(rng);
    a.SetJoints(q);
    b.SetJoints(q);
    const Eigen::Isometry3d F_a = a.TcpPose() * T_a, F_b = b.TcpPose() * T_b;
    worst = std::max(worst, PoseError(F_a, F_b));
    // and the closed form of the URDF arm agrees with MuJoCo's flange
    worst = std::max(worst, PoseError(urdf.kinematics().X_WR * planner::ForwardKinematics(arm, q.head<6>()), F_a));
  }
  EXPECT_LT(worst, 1e-6) << "flange of the URDF arm vs the MJCF arm and the closed form, mm";
}

TEST_F(UrdfArmTest, IkOnEveryBranchPutsMujocosTcpOnThePose) {
  const CellModel cell = LoadCell(Settings(WriteUrdf(Urdf())));
  const planner::CellKinematics kin = cell.kinematics();
  CellState state(cell);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  int checked = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::Vector3d p_W(1000 + 250 * u(rng), 250 * u(rng), 600 + 150 * u(rng));
    const Eigen::Vector3d dir = Eigen::Vector3d(0.7 * u(rng), 0.7 * u(rng), 1.0).normalized();
    const Eigen::Isometry3d X_WT = planner::TorchPose(kin, p_W, dir);
    const Eigen::Isometry3d X_RF = kin.X_WR.inverse() * X_WT * kin.X_FT.inverse();
    const planner::IkSolutions ik = planner::SolveIk(kin.arm, X_RF, nullptr);
    for (int i = 0; i < ik.count; ++i) {
      planner::Joints8 q = planner::Joints8::Zero();
      q.head<6>() = ik.solutions[i].q;
      state.SetJoints(q);
      worst = std::max(worst, PoseError(state.TcpPose(), X_WT));
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
  EXPECT_LT(worst, 1e-6);
}

TEST_F(UrdfArmTest, WallIsCheckedEndToEnd) {
  const CellSettings settings = Settings(WriteUrdf(Urdf()));
  const CellModel cell = LoadCell(settings);
  const CheckReport r = CheckPlan(cell, testing::RectangleWall(4, 80.0, 40.0, 2.0, 400.0 / 60.0), settings, 100.0,
                                  nullptr);
  EXPECT_GT(r.samples, 100u);
  EXPECT_EQ(r.ik, "closed_form");
  EXPECT_EQ(r.robot.source, settings.robot_urdf.string());
  for (const CheckViolation& v : r.violations) {
    EXPECT_NE(v.kind, ViolationKind::kUnreachable) << "the wall lies well inside the KR 16's reach";
  }
}

TEST_F(UrdfArmTest, RosPackagePathIsHonoured) {
  CellSettings settings = Settings(WriteUrdf(Urdf()));
  settings.robot_package_paths.clear();
  ::setenv("ROS_PACKAGE_PATH", (dir_ / "nowhere").string().c_str(), 1);
  EXPECT_THAT(ErrorOf(settings), HasSubstr("unknown package 'waam_kr16_support'"));
  EXPECT_THAT(ErrorOf(settings), HasSubstr((dir_ / "nowhere").string()));
  ::setenv("ROS_PACKAGE_PATH", ((dir_ / "nowhere").string() + ":" + (dir_ / "pkgs").string()).c_str(), 1);
  EXPECT_EQ(ErrorOf(settings), "no error");
  ::unsetenv("ROS_PACKAGE_PATH");
}

TEST_F(UrdfArmTest, BadUrdfsAreOneLineNamingTheFileAndElement) {
  const std::string good = Urdf();
  auto with = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const std::size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    s.replace(at, from.size(), to);
    return Settings(WriteUrdf(s));
  };
  // Not a serial chain of six revolute joints.
  {
    const std::string e = ErrorOf(with("name=\"joint_a3\" type=\"revolute\"", "name=\"joint_a3\" type=\"fixed\""));
    EXPECT_THAT(e, HasSubstr("kr16_2.urdf:"));
    EXPECT_THAT(e, HasSubstr("5 revolute joints"));
  }
  EXPECT_THAT(ErrorOf(with("name=\"joint_a3\" type=\"revolute\"", "name=\"joint_a3\" type=\"prismatic\"")),
              HasSubstr("joint 'joint_a3' is prismatic"));
  // A joints entry the URDF lacks.
  {
    CellSettings s = Settings(WriteUrdf(good));
    s.robot_joints = {"joint_a1", "joint_a2", "joint_a3", "joint_a4", "joint_a5", "joint_7"};
    EXPECT_THAT(ErrorOf(s), HasSubstr("names joint 'joint_7', which the URDF lacks"));
  }
  // A missing mesh; an unknown package naming the directory searched.
  EXPECT_THAT(ErrorOf(with("collision/link_3.stl", "collision/link_33.stl")),
              HasSubstr("link_33.stl not found"));
  {
    const std::string e = ErrorOf(with("package://waam_kr16_support/meshes/kr16/collision/link_2.stl",
                                       "package://waam_kr99_support/meshes/link_2.stl"));
    EXPECT_THAT(e, HasSubstr("unknown package 'waam_kr99_support'"));
    EXPECT_THAT(e, HasSubstr((dir_ / "pkgs").string()));
  }
  // A limit without velocity.
  {
    const std::string e = ErrorOf(with("velocity=", "speed="));
    EXPECT_THAT(e, HasSubstr("without velocity"));
    EXPECT_THAT(e, HasSubstr("joint_a1"));
  }
  // A mesh format MuJoCo does not read.
  EXPECT_THAT(ErrorOf(with("collision/link_4.stl", "collision/link_4.dae")), HasSubstr("not found"));
  // An ASCII STL (MuJoCo 2.2 reads binary STL only).
  {
    std::ofstream(pkg_ / "meshes" / "kr16" / "collision" / "ascii.stl") << "solid a\nendsolid a\n";
    EXPECT_THAT(ErrorOf(with("collision/link_5.stl", "collision/ascii.stl")), HasSubstr("ASCII STL"));
  }
  // Not XML; a xacro.
  EXPECT_THAT(ErrorOf(Settings(WriteUrdf("<robot name=\"x\"><link name=\"a\"></robot>"))),
              HasSubstr("not a readable XML file"));
  {
    const fs::path xacro = pkg_ / "urdf" / "kr16_2.urdf.xacro";
    std::ofstream(xacro) << good;
    EXPECT_THAT(ErrorOf(Settings(xacro)), HasSubstr("run `xacro"));
  }
  // A cycle of joints: link_1 hung below link_6 instead of base_link.
  EXPECT_THAT(ErrorOf(with("<parent link=\"base_link\"/>\n    <child link=\"link_1\"/>",
                           "<parent link=\"link_6\"/>\n    <child link=\"link_1\"/>")),
              HasSubstr("a cycle of joints"));
  // Every message is one line.
  EXPECT_EQ(ErrorOf(with("velocity=", "speed=")).find('\n'), std::string::npos);
}

}  // namespace
}  // namespace waam::twin
