// Yaskawa INFORM job (.JBI) writer: the arm and the positioner as one control group (RB1 + station ST1), C
// positions in the robot frame, EC station positions in encoder pulses.
#pragma once

#include <array>
#include <string>

#include <Eigen/Geometry>

#include "planner/program/robot_program.h"

namespace waam::planner {

struct YaskawaJbiOptions {
  // The robot frame the C positions are written in (///POSTYPE ROBOT), relative to the cell's arm base frame R: the
  // user frame of the program table goes through X_RU, mm.
  Eigen::Isometry3d X_RU = Eigen::Isometry3d::Identity();
  int tool = 1;                               // ///TOOL n: the torch
  int arc_start_file = 1;                     // ARCON ASF#(n)
  int arc_end_file = 1;                       // ARCOF AEF#(n)
  // Encoder pulses per degree of the station's two axes (tilt, rotation), the controller's parameters; > 0.
  std::array<double, 2> station_pulses_per_deg = {0.0, 0.0};
};

// The JBI text: /JOB, //NAME (at most 32 characters, upper case), //POS with ///NPOS n,0,n,0,0,0, C0000k=X,Y,Z mm,
// Rx,Ry,Rz deg (R = Rz Ry Rx, fixed angles) under ///POSTYPE ROBOT with ///RCONF from the IK branch, EC0000k=tilt,
// rotation pulses under ///POSTYPE PULSE; //INST with ///GROUP1 RB1,ST1, MOVJ to the first point, MOVL (V= mm/s)
// to every other one with its EC position, ARCON ASF#(n) before a pass's first weld move and ARCOF AEF#(n) after
// its last, END. Deterministic: ///DATE is a fixed date, not the clock. Throws InputError when the station's
// pulses per degree are not > 0.
std::string ProgramToYaskawaJbi(const RobotProgram& program, const YaskawaJbiOptions& options);

}  // namespace waam::planner
