// FANUC LS writer. Kept apart from the table so other dialects (KUKA KRL, ABB RAPID) can be added beside it.
#include "planner/program/fanuc_ls.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "models/core/numbers.h"

namespace waam::planner {
namespace {

int Turn(double q_rad) {
  const double deg = q_rad * 180.0 / kPi;
  return deg > 180.0 ? 1 : (deg < -180.0 ? -1 : 0);
}

}  // namespace

std::string FanucConfig(const ProgramPoint& p) {
  // Wrist: N with j5 < 0 (the flange pointing down in the usual welding posture), F otherwise; elbow: U for the
  // elbow-up closed-form branch; shoulder: T in front of j1, B reaching over the back.
  const bool back = (p.branch & 1) != 0;
  const bool elbow_down = (p.branch & 2) != 0;
  char text[64];
  std::snprintf(text, sizeof(text), "%c %c %c, %d, %d, %d", p.q[4] > 0.0 ? 'F' : 'N', elbow_down ? 'D' : 'U',
                back ? 'B' : 'T', Turn(p.q[0]), Turn(p.q[3]), Turn(p.q[5]));
  return text;
}

std::string ProgramToFanucLs(const RobotProgram& program, const FanucLsOptions& options) {
  std::string mn;
  int line = 0;
  char buf[512];
  auto emit = [&](const std::string& text) {
    std::snprintf(buf, sizeof(buf), "%4d:  %s ;\n", ++line, text.c_str());
    mn += buf;
  };
  bool arc_on = false;
  for (std::size_t i = 0; i < program.points.size(); ++i) {
    const ProgramPoint& p = program.points[i];
    if (p.weld && !arc_on) {
      std::snprintf(buf, sizeof(buf), "Arc Start[%d]", options.arc_schedule);
      emit(buf);
      arc_on = true;
    } else if (!p.weld && arc_on) {
      std::snprintf(buf, sizeof(buf), "Arc End[%d]", options.arc_schedule);
      emit(buf);
      arc_on = false;
    }
    if (i == 0) {
      std::snprintf(buf, sizeof(buf), "J P[%zu] 20%% FINE", i + 1);
    } else if (p.weld) {
      // Weld speeds in cm/min, the welding unit of the controller (400 mm/min = 40cm/min, no rounding to mm/s).
      const int speed = std::max(1, static_cast<int>(std::lround(p.speed_mm_s * 6.0)));
      // COORD needs a positioner group to lead.
      const bool coord = options.coordinated && program.positioner != PositionerType::kNone;
      std::snprintf(buf, sizeof(buf), "L P[%zu] %dcm/min CNT100%s", i + 1, speed, coord ? " COORD" : "");
    } else {
      const int speed = std::max(1, static_cast<int>(std::lround(p.speed_mm_s)));
      std::snprintf(buf, sizeof(buf), "L P[%zu] %dmm/sec FINE", i + 1, speed);
    }
    emit(buf);
  }
  if (arc_on) {
    std::snprintf(buf, sizeof(buf), "Arc End[%d]", options.arc_schedule);
    emit(buf);
  }

  std::string pos;
  for (std::size_t i = 0; i < program.points.size(); ++i) {
    const ProgramPoint& p = program.points[i];
    std::snprintf(buf, sizeof(buf),
                  "P[%zu]{\n   GP1:\n\tUF : %d, UT : %d,\t\tCONFIG : '%s',\n"
                  "\tX = %10.3f  mm,\tY = %10.3f  mm,\tZ = %10.3f  mm,\n"
                  "\tW = %10.3f deg,\tP = %10.3f deg,\tR = %10.3f deg\n",
                  i + 1, options.user_frame, options.tool_frame, FanucConfig(p).c_str(),
                  ProgramValue(p.tcp_mm.x()), ProgramValue(p.tcp_mm.y()), ProgramValue(p.tcp_mm.z()),
                  ProgramValue(p.c_deg), ProgramValue(p.b_deg), ProgramValue(p.a_deg));
    pos += buf;
    // Motion group 2 is the positioner: J1 tilt and J2 rotation, a turntable's J1 its rotation, none without one.
    if (program.positioner == PositionerType::kTiltRotate) {
      std::snprintf(buf, sizeof(buf), "   GP2:\n\tUF : %d, UT : %d,\n\tJ1 = %10.3f deg,\tJ2 = %10.3f deg\n};\n",
                    options.user_frame, options.tool_frame, ProgramValue(p.tilt_deg), ProgramValue(p.rotation_deg));
    } else if (program.positioner == PositionerType::kTurntable) {
      std::snprintf(buf, sizeof(buf), "   GP2:\n\tUF : %d, UT : %d,\n\tJ1 = %10.3f deg\n};\n", options.user_frame,
                    options.tool_frame, ProgramValue(p.rotation_deg));
    } else {
      std::snprintf(buf, sizeof(buf), "};\n");
    }
    pos += buf;
  }

  std::string out = "/PROG  " + program.name + "\n/ATTR\nOWNER\t\t= MNEDITOR;\nCOMMENT\t\t= \"waam-twin\";\n";
  std::snprintf(buf, sizeof(buf), "LINE_COUNT\t= %d;\n", line);
  out += buf;
  out +=
      "PROTECT\t\t= READ_WRITE;\nTCD:  STACK_SIZE\t= 0,\n      TASK_PRIORITY\t= 50,\n      TIME_SLICE\t= 0,\n"
      "      BUSY_LAMP_OFF\t= 0,\n      ABORT_REQUEST\t= 0,\n      PAUSE_REQUEST\t= 0;\n"
      "DEFAULT_GROUP\t= " + std::string(program.positioner == PositionerType::kNone ? "1,*" : "1,1") +
      ",*,*,*;\nCONTROL_CODE\t= 00000000 00000000;\n/MN\n";
  out += mn;
  out += "/POS\n";
  out += pos;
  out += "/END\n";
  return out;
}

}  // namespace waam::planner
