// G-code writer for gantry or CNC-style WAAM machines: the TCP in the part frame, the positioner as rotary axes.
#pragma once

#include <string>

#include "planner/program/robot_program.h"

namespace waam::planner {

struct GcodeOptions {
  int arc_on_m = 3;   // M-code that starts the arc
  int arc_off_m = 5;  // M-code that stops it
};

// The G-code text: G21 G90, then one G1 per point (X Y Z = TCP in the part frame, mm; A = positioner tilt, C =
// rotation, deg; A3= B3= C3= the tool direction as Sinumerik ORIVECT writes it, whenever it changes, +z at the start; F in mm/min
// whenever it changes), the arc-on M-code before the first weld move of a pass and the arc-off one after its last,
// M30 at the end. Travel moves are G1 at their speed with the arc off. Deterministic.
std::string ProgramToGcode(const RobotProgram& program, const GcodeOptions& options);

}  // namespace waam::planner
