// ABB RAPID writer.
#include "planner/program/abb_rapid.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "models/core/numbers.h"

namespace waam::planner {
namespace {

// RAPID pose [[x,y,z],[q1,q2,q3,q4]] with q1 the scalar part, kept >= 0.
std::string RapidPose(const Eigen::Isometry3d& X) {
  Eigen::Quaterniond q(X.linear());
  q.normalize();
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  char buf[256];
  std::snprintf(buf, sizeof(buf), "[[%.3f,%.3f,%.3f],[%.9f,%.9f,%.9f,%.9f]]", ProgramValue(X.translation().x()),
                ProgramValue(X.translation().y()), ProgramValue(X.translation().z()), q.w(), q.x(), q.y(), q.z());
  return buf;
}

int Quadrant(double q_rad) { return static_cast<int>(std::floor(q_rad / (kPi / 2) + 1e-12)); }

}  // namespace

std::string ProgramToAbbRapid(const RobotProgram& program, const AbbRapidOptions& options) {
  std::string name = program.name.substr(0, 32);
  char buf[512];
  std::string data, proc;
  // ABB's flange frame has z along the flange normal, x down at the zero pose; the twin's has x along the normal:
  // x_abb = -z_F, y_abb = y_F, z_abb = x_F.
  // X_F_Fabb has ABB's axes as columns in F; the tool's tframe is in Fabb: X_Fabb_T = X_F_Fabb^-1 X_FT.
  Eigen::Isometry3d X_F_Fabb = Eigen::Isometry3d::Identity();
  X_F_Fabb.linear() << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  data += "  PERS tooldata tWAAM:=[TRUE," + RapidPose(X_F_Fabb.inverse() * options.X_FT) +
          ",[5,[0,0,100],[1,0,0,0],0,0,0]];\n";
  data += "  TASK PERS wobjdata wobjWAAM:=[FALSE,TRUE,\"\"," + RapidPose(options.X_RU) +
          ",[[0,0,0],[1,0,0,0]]];\n";
  data += "  PERS seamdata seamWAAM:=[0.5,0.5,[0,0,0,0,0,0,0,0,0],0,0,0,0,0,[0,0,0,0,0,0,0,0,0],0,0,"
          "[0,0,0,0,0,0,0,0,0],0,0,[0,0,0,0,0,0,0,0,0],0];\n";
  std::map<long long, std::string> welds, speeds;
  auto speed_key = [](double v) { return std::llround(v * 1000.0); };
  for (const ProgramPoint& p : program.points) {
    std::map<long long, std::string>& table = p.weld ? welds : speeds;
    const long long key = speed_key(p.speed_mm_s);
    if (table.count(key)) continue;
    const std::string id = (p.weld ? "wdWAAM" : "vWAAM") + std::to_string(table.size() + 1);
    table[key] = id;
    if (p.weld) {
      std::snprintf(buf, sizeof(buf), "  PERS welddata %s:=[%.3f,0,[0,0,0,0,0,0,0,0,0],[0,0,0,0,0,0,0,0,0]];\n",
                    id.c_str(), p.speed_mm_s);
    } else {
      std::snprintf(buf, sizeof(buf), "  CONST speeddata %s:=[%.3f,500,5000,1000];\n", id.c_str(), p.speed_mm_s);
    }
    data += buf;
  }
  // Arc-on approach and welded moves run their travel speed through speeddata too (ArcLStart moves at it).
  const std::string weld_speed = speeds.empty() ? "v100" : speeds.begin()->second;
  for (std::size_t i = 0; i < program.points.size(); ++i) {
    const ProgramPoint& p = program.points[i];
    Eigen::Isometry3d X_UT = Eigen::Isometry3d::Identity();
    X_UT.translation() = p.tcp_mm;
    X_UT.linear() = (Eigen::AngleAxisd(p.a_deg * kPi / 180.0, Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(p.b_deg * kPi / 180.0, Eigen::Vector3d::UnitY()) *
                     Eigen::AngleAxisd(p.c_deg * kPi / 180.0, Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
    const int cfx = ((p.branch & 1) ? 4 : 0) + ((p.branch & 2) ? 2 : 0) + ((p.branch & 4) ? 1 : 0);
    // extjoint: eax_a, eax_b the positioner's tilt and rotation, a turntable's eax_a its rotation; 9E+09 unused.
    char eax[96];
    if (program.positioner == PositionerType::kTiltRotate) {
      std::snprintf(eax, sizeof(eax), "%.3f,%.3f", ProgramValue(p.tilt_deg), ProgramValue(p.rotation_deg));
    } else if (program.positioner == PositionerType::kTurntable) {
      std::snprintf(eax, sizeof(eax), "%.3f,9E+09", ProgramValue(p.rotation_deg));
    } else {
      std::snprintf(eax, sizeof(eax), "9E+09,9E+09");
    }
    std::snprintf(buf, sizeof(buf), "  CONST robtarget pWAAM%zu:=%s,[%d,%d,%d,%d],[%s,9E+09,9E+09,9E+09,9E+09]];\n",
                  i + 1, RapidPose(X_UT).substr(0, RapidPose(X_UT).size() - 1).c_str(), Quadrant(p.q[0]),
                  Quadrant(p.q[3]), Quadrant(p.q[5]), cfx, eax);
    data += buf;
    const bool next_weld = i + 1 < program.points.size() && program.points[i + 1].weld;
    const std::string target = "pWAAM" + std::to_string(i + 1);
    const std::string tail = "tWAAM\\WObj:=wobjWAAM;\n";
    if (p.weld) {
      const std::string& wd = welds[speed_key(p.speed_mm_s)];
      proc += "    " + std::string(next_weld ? "ArcL " : "ArcLEnd ") + target + "," + weld_speed + ",seamWAAM," + wd +
              (next_weld ? ",z1," : ",fine,") + tail;
    } else {
      const std::string& v = speeds[speed_key(p.speed_mm_s)];
      if (next_weld) {
        proc += "    ArcLStart " + target + "," + v + ",seamWAAM," + welds[speed_key(program.points[i + 1].speed_mm_s)] +
                ",fine," + tail;
      } else {
        proc += "    " + std::string(i == 0 ? "MoveJ " : "MoveL ") + target + "," + v + ",fine," + tail;
      }
    }
  }
  std::string out = "MODULE " + name + "\n";
  out += program.positioner == PositionerType::kTiltRotate
             ? "  ! waam-twin: positions in wobjWAAM; external axes eax_a = positioner tilt, eax_b = rotation (deg)\n"
         : program.positioner == PositionerType::kTurntable
             ? "  ! waam-twin: positions in wobjWAAM; external axis eax_a = turntable rotation (deg)\n"
             : "  ! waam-twin: positions in wobjWAAM; no external axes\n";
  out += data;
  out += "\n  PROC main()\n";
  out += "    ConfL\\Off;\n";
  out += proc;
  out += "  ENDPROC\nENDMODULE\n";
  return out;
}

}  // namespace waam::planner
