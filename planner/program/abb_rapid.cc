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

long long SpeedKey(double v) { return std::llround(v * 1000.0); }

// The module's tool (tWAAM, in ABB's flange frame), work object (wobjWAAM, the user frame in the robot base) and
// seam data declarations.
std::string ToolAndFrames(const AbbRapidOptions& options) {
  // ABB's flange frame has z along the flange normal, x down at the zero pose; the twin's has x along the normal:
  // x_abb = -z_F, y_abb = y_F, z_abb = x_F.
  // X_F_Fabb has ABB's axes as columns in F; the tool's tframe is in Fabb: X_Fabb_T = X_F_Fabb^-1 X_FT.
  Eigen::Isometry3d X_F_Fabb = Eigen::Isometry3d::Identity();
  X_F_Fabb.linear() << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  std::string data = "  PERS tooldata tWAAM:=[TRUE," + RapidPose(X_F_Fabb.inverse() * options.X_FT) +
                     ",[5,[0,0,100],[1,0,0,0],0,0,0]];\n";
  data += "  TASK PERS wobjdata wobjWAAM:=[FALSE,TRUE,\"\"," + RapidPose(options.X_RU) + ",[[0,0,0],[1,0,0,0]]];\n";
  data += "  PERS seamdata seamWAAM:=[0.5,0.5,[0,0,0,0,0,0,0,0,0],0,0,0,0,0,[0,0,0,0,0,0,0,0,0],0,0,"
          "[0,0,0,0,0,0,0,0,0],0,0,[0,0,0,0,0,0,0,0,0],0];\n";
  return data;
}

// The program's distinct speeds (by SpeedKey): welddata wdWAAMn of the weld moves, speeddata vWAAMn of the others.
struct SpeedTables {
  std::map<long long, std::string> welds, speeds;
};

// Fills `tables` with one welddata or speeddata per distinct speed, numbered in the order of first use, and returns
// their declarations.
std::string SpeedData(const RobotProgram& program, SpeedTables* tables) {
  std::string data;
  char buf[512];
  for (const ProgramPoint& p : program.points) {
    std::map<long long, std::string>& table = p.weld ? tables->welds : tables->speeds;
    const long long key = SpeedKey(p.speed_mm_s);
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
  return data;
}

// The robtarget pWAAM<i + 1> of point `p`: pose in wobjWAAM, confdata from the joints' quadrants and the IK branch,
// extjoint eax_a, eax_b the positioner's tilt and rotation (a turntable's eax_a its rotation; 9E+09 unused).
std::string RobTarget(const RobotProgram& program, const ProgramPoint& p, std::size_t i) {
  Eigen::Isometry3d X_UT = Eigen::Isometry3d::Identity();
  X_UT.translation() = p.tcp_mm;
  X_UT.linear() = (Eigen::AngleAxisd(p.a_deg * kPi / 180.0, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(p.b_deg * kPi / 180.0, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(p.c_deg * kPi / 180.0, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  const int cfx = ((p.branch & 1) ? 4 : 0) + ((p.branch & 2) ? 2 : 0) + ((p.branch & 4) ? 1 : 0);
  char eax[96];
  if (program.positioner == PositionerType::kTiltRotate) {
    std::snprintf(eax, sizeof(eax), "%.3f,%.3f", ProgramValue(p.tilt_deg), ProgramValue(p.rotation_deg));
  } else if (program.positioner == PositionerType::kTurntable) {
    std::snprintf(eax, sizeof(eax), "%.3f,9E+09", ProgramValue(p.rotation_deg));
  } else {
    std::snprintf(eax, sizeof(eax), "9E+09,9E+09");
  }
  char buf[512];
  std::snprintf(buf, sizeof(buf), "  CONST robtarget pWAAM%zu:=%s,[%d,%d,%d,%d],[%s,9E+09,9E+09,9E+09,9E+09]];\n",
                i + 1, RapidPose(X_UT).substr(0, RapidPose(X_UT).size() - 1).c_str(), Quadrant(p.q[0]),
                Quadrant(p.q[3]), Quadrant(p.q[5]), cfx, eax);
  return buf;
}

// The instruction that moves to point i: ArcL (ArcLEnd at a pass's end) for a weld move, ArcLStart before a pass,
// MoveJ to the first point, MoveL otherwise. Arc-on approach and welded moves run their travel speed through
// speeddata too (ArcLStart moves at it): `weld_speed`.
std::string MoveTo(const RobotProgram& program, std::size_t i, SpeedTables& tables, const std::string& weld_speed) {
  const ProgramPoint& p = program.points[i];
  const bool next_weld = i + 1 < program.points.size() && program.points[i + 1].weld;
  const std::string target = "pWAAM" + std::to_string(i + 1);
  const std::string tail = "tWAAM\\WObj:=wobjWAAM;\n";
  if (p.weld) {
    const std::string& wd = tables.welds[SpeedKey(p.speed_mm_s)];
    return "    " + std::string(next_weld ? "ArcL " : "ArcLEnd ") + target + "," + weld_speed + ",seamWAAM," + wd +
           (next_weld ? ",z1," : ",fine,") + tail;
  }
  const std::string& v = tables.speeds[SpeedKey(p.speed_mm_s)];
  if (next_weld) {
    return "    ArcLStart " + target + "," + v + ",seamWAAM," +
           tables.welds[SpeedKey(program.points[i + 1].speed_mm_s)] + ",fine," + tail;
  }
  return "    " + std::string(i == 0 ? "MoveJ " : "MoveL ") + target + "," + v + ",fine," + tail;
}

}  // namespace

std::string ProgramToAbbRapid(const RobotProgram& program, const AbbRapidOptions& options) {
  std::string name = program.name.substr(0, 32);
  std::string data = ToolAndFrames(options);
  SpeedTables tables;
  data += SpeedData(program, &tables);
  const std::string weld_speed = tables.speeds.empty() ? "v100" : tables.speeds.begin()->second;
  std::string proc;
  for (std::size_t i = 0; i < program.points.size(); ++i) {
    data += RobTarget(program, program.points[i], i);
    proc += MoveTo(program, i, tables, weld_speed);
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
