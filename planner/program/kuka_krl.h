// KUKA KRL writer: a .src with the motions and a .dat with the E6POS positions (S and T from the IK branch, E1/E2
// the positioner).
#pragma once

#include <string>

#include <Eigen/Geometry>

#include "planner/program/robot_program.h"

namespace waam::planner {

struct KukaKrlOptions {
  // The base ($BASE, written in the .src) the positions are in, relative to the robot's base frame R, mm.
  Eigen::Isometry3d X_RU = Eigen::Isometry3d::Identity();
  int arc_output = 1;  // $OUT[n] that switches the arc
};

struct KukaKrlFiles {
  std::string src;
  std::string dat;
};

// DEF <name>() with $BASE as a frame literal, PTP to the first point, LIN to every other one with $VEL.CP (m/s)
// whenever the speed changes, $OUT[arc_output]=TRUE before a pass's first weld move and FALSE after its last; the
// .dat declares DECL E6POS XPn={X, Y, Z mm, A, B, C deg, S, T, E1 tilt, E2 rotation deg}. S bit 0 shoulder back,
// bit 1 elbow down, bit 2 wrist flipped (the IK branch); T bit k set when axis k+1 is negative. Deterministic.
KukaKrlFiles ProgramToKukaKrl(const RobotProgram& program, const KukaKrlOptions& options);

}  // namespace waam::planner
