// FANUC LS (ASCII teach-pendant) program writer: the arm as motion group 1, the positioner as group 2.
#pragma once

#include <string>

#include "planner/program/robot_program.h"

namespace waam::planner {

struct FanucLsOptions {
  int user_frame = 0;      // UF of the positions: 0, the FANUC world frame of BuildProgram (else it must be taught
                           // as this UF, and the reader needs program.frames.uframe.<n>)
  int tool_frame = 1;      // UT: the torch TCP
  int arc_schedule = 1;    // Arc Start[n] / Arc End[n]
  bool coordinated = true; // weld moves with the COORD option (coordinated motion, positioner leading)
};

// The LS text: header, one motion line per program point (L moves; weld moves CNT100 in cm/min, arc-off moves FINE
// in mm/sec), Arc Start before the first weld move of a pass and Arc End after its last, and the /POS section with GP1
// as Cartesian X Y Z W P R (W = C, P = B, R = A of the table) with the configuration string, GP2 as joint angles.
// Deterministic: no date from the clock.
std::string ProgramToFanucLs(const RobotProgram& program, const FanucLsOptions& options);

// FANUC configuration string of a program point, e.g. "N U T, 0, 0, 0" (wrist flip, elbow up/down, shoulder
// top/back, turn numbers of j1, j4, j6).
std::string FanucConfig(const ProgramPoint& point);

}  // namespace waam::planner
