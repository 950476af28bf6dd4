// KUKA KRL writer.
#include "planner/program/kuka_krl.h"

#include <cctype>
#include <cmath>
#include <cstdio>

#include "models/core/numbers.h"
#include "planner/program/robot_program.h"

namespace waam::planner {
namespace {

// KRL frame literal {X, Y, Z, A, B, C} of a pose (mm, deg; R = Rz(A) Ry(B) Rx(C)).
std::string KrlFrame(const Eigen::Isometry3d& X) {
  const Eigen::Vector3d abc = EulerZyx(X.linear()) * kDeg;
  char buf[256];
  std::snprintf(buf, sizeof(buf), "{X %.3f,Y %.3f,Z %.3f,A %.4f,B %.4f,C %.4f}", ProgramValue(X.translation().x()),
                ProgramValue(X.translation().y()), ProgramValue(X.translation().z()), ProgramValue(abc[0]),
                ProgramValue(abc[1]), ProgramValue(abc[2]));
  return buf;
}

}  // namespace

KukaKrlFiles ProgramToKukaKrl(const RobotProgram& program, const KukaKrlOptions& options) {
  std::string name = program.name.substr(0, 24);
  KukaKrlFiles out;
  char buf[512];
  out.src = "&ACCESS RVP\n&REL 1\nDEF " + name + "( )\n;FOLD INI\n  BAS (#INITMOV,0 )\n;ENDFOLD (INI)\n";
  out.src += program.positioner == PositionerType::kTiltRotate ? "; waam-twin: positions in $BASE, E1 = positioner tilt, E2 = rotation (deg)\n"
             : program.positioner == PositionerType::kTurntable   ? "; waam-twin: positions in $BASE, E1 = turntable rotation (deg)\n"
                                                                  : "; waam-twin: positions in $BASE, no external axes\n";
  out.src += "$BASE=" + KrlFrame(options.X_RU) + "\n$APO.CDIS=1.0\n";
  out.dat = "&ACCESS RVP\n&REL 1\nDEFDAT " + name + "\n";
  bool arc_on = false;
  double vel = -1.0;
  for (std::size_t i = 0; i < program.points.size(); ++i) {
    const ProgramPoint& p = program.points[i];
    if (p.weld && !arc_on) {
      std::snprintf(buf, sizeof(buf), "$OUT[%d]=TRUE\n", options.arc_output);
      out.src += buf;
      arc_on = true;
    } else if (!p.weld && arc_on) {
      std::snprintf(buf, sizeof(buf), "$OUT[%d]=FALSE\n", options.arc_output);
      out.src += buf;
      arc_on = false;
    }
    int t = 0;
    for (int k = 0; k < 6; ++k) t |= (p.q[k] < 0.0 ? 1 : 0) << k;
    const int s = ((p.branch & 1) ? 1 : 0) | ((p.branch & 2) ? 2 : 0) | ((p.branch & 4) ? 4 : 0);
    // E1, E2 the positioner's tilt and rotation; a turntable's E1 its rotation; unused axes 0.0 as KSS writes them.
    const double e1 = program.positioner == PositionerType::kTiltRotate  ? p.tilt_deg
                      : program.positioner == PositionerType::kTurntable ? p.rotation_deg
                                                                          : 0.0;
    const double e2 = program.positioner == PositionerType::kTiltRotate ? p.rotation_deg : 0.0;
    std::snprintf(buf, sizeof(buf),
                  "DECL E6POS XP%zu={X %.3f,Y %.3f,Z %.3f,A %.4f,B %.4f,C %.4f,S %d,T %d,E1 %.4f,E2 %.4f,E3 0.0,E4 "
                  "0.0,E5 0.0,E6 0.0}\n",
                  i + 1, ProgramValue(p.tcp_mm.x()), ProgramValue(p.tcp_mm.y()), ProgramValue(p.tcp_mm.z()),
                  ProgramValue(p.a_deg), ProgramValue(p.b_deg), ProgramValue(p.c_deg), s, t, ProgramValue(e1),
                  ProgramValue(e2));
    out.dat += buf;
    if (i == 0) {
      std::snprintf(buf, sizeof(buf), "PTP XP%zu\n", i + 1);
    } else {
      const double v = std::round(p.speed_mm_s * 1e3) / 1e6;  // m/s, to 1 um/s
      if (v != vel) {
        std::snprintf(buf, sizeof(buf), "$VEL.CP=%.6f\n", v);
        out.src += buf;
        vel = v;
      }
      std::snprintf(buf, sizeof(buf), "LIN XP%zu C_DIS\n", i + 1);
    }
    out.src += buf;
  }
  if (arc_on) {
    std::snprintf(buf, sizeof(buf), "$OUT[%d]=FALSE\n", options.arc_output);
    out.src += buf;
  }
  out.src += "END\n";
  out.dat += "ENDDAT\n";
  return out;
}

}  // namespace waam::planner
