// G-code writer.
#include "planner/program/gcode.h"

#include <cmath>
#include <cstdio>

namespace waam::planner {

std::string ProgramToGcode(const RobotProgram& program, const GcodeOptions& options) {
  std::string out = "; " + program.name + " (waam-twin)\n";
  // The positioner words the cell has: A (tilt) and C (rotation), C alone for a turntable, none without one.
  const bool tilt = HasAxis(program.positioner, 6), rotation = HasAxis(program.positioner, 7);
  out += std::string("; X Y Z: TCP in the part frame (mm); ") +
         (tilt ? "A: positioner tilt, C: positioner rotation (deg); "
               : (rotation ? "C: turntable rotation (deg); " : "")) +
         "A3 B3 C3: tool direction\n";
  char buf[320];
  std::snprintf(buf, sizeof(buf), "; arc on M%d, arc off M%d\nG21 G90\n", options.arc_on_m, options.arc_off_m);
  out += buf;
  bool arc_on = false;
  double feed = -1.0;
  Eigen::Vector3d last_dir = Eigen::Vector3d::UnitZ();  // the tool direction is modal, +z at the start
  for (std::size_t i = 0; i < program.points.size(); ++i) {
    const ProgramPoint& p = program.points[i];
    if (p.weld && !arc_on) {
      std::snprintf(buf, sizeof(buf), "M%d\n", options.arc_on_m);
      out += buf;
      arc_on = true;
    } else if (!p.weld && arc_on) {
      std::snprintf(buf, sizeof(buf), "M%d\n", options.arc_off_m);
      out += buf;
      arc_on = false;
    }
    std::snprintf(buf, sizeof(buf), "G1 X%.3f Y%.3f Z%.3f", ProgramValue(p.p_P.x()), ProgramValue(p.p_P.y()),
                  ProgramValue(p.p_P.z()));
    out += buf;
    if (tilt) {
      std::snprintf(buf, sizeof(buf), " A%.3f", ProgramValue(p.tilt_deg));
      out += buf;
    }
    if (rotation) {
      std::snprintf(buf, sizeof(buf), " C%.3f", ProgramValue(p.rotation_deg));
      out += buf;
    }
    const Eigen::Vector3d d = p.tool_dir_P.normalized();
    if ((d - last_dir).norm() > 1e-9) {
      last_dir = d;
      std::snprintf(buf, sizeof(buf), " A3=%.7f B3=%.7f C3=%.7f", ProgramValue(d.x()), ProgramValue(d.y()),
                    ProgramValue(d.z()));
      out += buf;
    }
    const double f = std::round(p.speed_mm_s * 60.0 * 1000.0) / 1000.0;
    if (f != feed) {
      std::snprintf(buf, sizeof(buf), " F%.3f", f);
      out += buf;
      feed = f;
    }
    out += "\n";
  }
  if (arc_on) {
    std::snprintf(buf, sizeof(buf), "M%d\n", options.arc_off_m);
    out += buf;
  }
  out += "M30\n";
  return out;
}

}  // namespace waam::planner
