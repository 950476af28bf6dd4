// Program points from the checked motion, torch Euler angles (eq. 5.20-5.22) and the CSV table writer.
#include "planner/program/robot_program.h"

#include <cctype>
#include <cmath>
#include <cstdio>

#include "models/core/numbers.h"

namespace waam::planner {

Eigen::Vector3d EulerZyx(const Eigen::Matrix3d& R) {
  // eq. 5.20: A = atan(R21 / R11); eq. 5.21: B = atan(-R31 / sqrt(R32^2 + R33^2)); eq. 5.22: C = atan(R32 / R33),
  // with the quadrant-correct atan2 (1-based indices in the dissertation).
  const double a = std::atan2(R(1, 0), R(0, 0));
  const double b = std::atan2(-R(2, 0), std::hypot(R(2, 1), R(2, 2)));
  const double c = std::atan2(R(2, 1), R(2, 2));
  return {a, b, c};
}

Eigen::Isometry3d ProgramUserFrame(const CellKinematics& cell) {
  Eigen::Isometry3d X_WU = cell.X_WR;  // FANUC world (user) frame: on j1 at the height of j2
  X_WU.translate(Eigen::Vector3d(0.0, 0.0, cell.arm.c1));
  return X_WU;
}

RobotProgram BuildProgram(const CellKinematics& cell, const std::vector<CellSample>& motion, const std::string& name) {
  RobotProgram program;
  for (char ch : name) {
    const unsigned char u = static_cast<unsigned char>(ch);
    program.name += std::isalnum(u) ? static_cast<char>(std::toupper(u)) : '_';
  }
  if (program.name.empty() || !std::isalpha(static_cast<unsigned char>(program.name[0]))) {
    program.name = "WAAM_" + program.name;
  }
  if (program.name.size() > 36) program.name.resize(36);

  program.positioner = cell.positioner.type;
  const Eigen::Isometry3d X_UW = ProgramUserFrame(cell).inverse();
  for (std::size_t i = 0; i < motion.size(); ++i) {
    if (i + 1 < motion.size() && motion[i + 1].point == motion[i].point) continue;
    const CellSample& s = motion[i];
    const Eigen::Isometry3d X_UT = X_UW * s.X_WT;
    const Eigen::Vector3d abc = EulerZyx(X_UT.linear());
    ProgramPoint p;
    p.point = s.point;
    p.layer = s.layer;
    p.tcp_mm = X_UT.translation();
    p.a_deg = abc[0] * kDeg;
    p.b_deg = abc[1] * kDeg;
    p.c_deg = abc[2] * kDeg;
    p.tilt_deg = s.q[6] * kDeg;
    p.rotation_deg = s.q[7] * kDeg;
    p.speed_mm_s = s.speed_mm_s;
    p.bead_height_mm = s.bead_height_mm;
    p.weld = s.weld;
    p.q = s.q.head<6>();
    p.branch = s.branch;
    const Eigen::Isometry3d X_WP = cell.X_WB * PartPose(cell.positioner, s.q[6], s.q[7]);
    p.p_P = s.p_P;
    p.tool_dir_P = -(X_WP.linear().transpose() * s.X_WT.linear().col(2));
    program.points.push_back(p);
  }
  return program;
}

std::string ProgramToCsv(const RobotProgram& program) {
  // The positioner columns the cell has: both, the rotation alone (turntable) or none.
  const bool tilt = HasAxis(program.positioner, 6), rotation = HasAxis(program.positioner, 7);
  std::string out = std::string("point,layer,x_mm,y_mm,z_mm,a_deg,b_deg,c_deg,") + (tilt ? "tilt_deg," : "") +
                    (rotation ? "rotation_deg," : "") + "speed_mm_min,bead_height_mm,weld\n";
  char line[320];
  for (const ProgramPoint& p : program.points) {
    std::snprintf(line, sizeof(line), "%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,", p.point, p.layer,
                  ProgramValue(p.tcp_mm.x()), ProgramValue(p.tcp_mm.y()), ProgramValue(p.tcp_mm.z()),
                  ProgramValue(p.a_deg), ProgramValue(p.b_deg), ProgramValue(p.c_deg));
    out += line;
    if (tilt) {
      std::snprintf(line, sizeof(line), "%.3f,", ProgramValue(p.tilt_deg));
      out += line;
    }
    if (rotation) {
      std::snprintf(line, sizeof(line), "%.3f,", ProgramValue(p.rotation_deg));
      out += line;
    }
    std::snprintf(line, sizeof(line), "%.1f,%.3f,%d\n", p.speed_mm_s * 60.0, p.bead_height_mm, p.weld ? 1 : 0);
    out += line;
  }
  return out;
}

}  // namespace waam::planner
