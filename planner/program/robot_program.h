// The eight-axis robot program in the dissertation's table form (Table 4 / Table 14): one row per path point with
// TCP position and torch Euler angles in the robot's world frame, positioner angles, speed, bead height, weld flag.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/kinematics/cell_motion.h"

namespace waam::planner {

// One program point.
struct ProgramPoint {
  int point = 0;                 // path point index over the whole plan
  int layer = 0;
  Eigen::Vector3d tcp_mm = Eigen::Vector3d::Zero();  // TCP in the FANUC world frame (R lifted to the j2 height), mm
  double a_deg = 0.0;            // yaw about z (eq. 5.20), deg
  double b_deg = 0.0;            // pitch about y (eq. 5.21), deg
  double c_deg = 0.0;            // roll about x (eq. 5.22), deg; R = Rz(A) Ry(B) Rx(C) (eq. 5.5)
  double tilt_deg = 0.0;         // positioner tilt, deg
  double rotation_deg = 0.0;     // positioner rotation, deg
  double speed_mm_s = 0.0;       // TCP speed relative to the part of the move ending here, mm/s
  double bead_height_mm = 0.0;
  bool weld = false;             // arc on for the move ending here
  Joints6 q = Joints6::Zero();   // arm joints, rad (for the configuration string)
  int branch = 0;                // IkSolution::branch
  Eigen::Vector3d p_P = Eigen::Vector3d::Zero();            // TCP in the part frame, mm (G-code writes it)
  Eigen::Vector3d tool_dir_P = Eigen::Vector3d::UnitZ();    // unit, from the TCP up the torch, part frame
};

struct RobotProgram {
  std::string name;              // program name (letters, digits, underscores)
  // The cell's positioner: the writers write only the external axes it has (tilt and rotation, the rotation alone,
  // or none).
  PositionerType positioner = PositionerType::kTiltRotate;
  std::vector<ProgramPoint> points;
};

// One program point per path point of the motion (the last sample of each move). The FANUC world frame is R
// shifted up by the arm's c1 (its origin is on j1 at the height of j2). `name` is turned into a valid program name.
RobotProgram BuildProgram(const CellKinematics& cell, const std::vector<CellSample>& motion, const std::string& name);

// The frame the program positions are written in: the FANUC world frame, R shifted up by the arm's c1 (on j1 at
// the height of j2), in W.
Eigen::Isometry3d ProgramUserFrame(const CellKinematics& cell);

// Euler angles (A, B, C) = (yaw z, pitch y, roll x) of a rotation, rad, by eq. 5.20-5.22.
Eigen::Vector3d EulerZyx(const Eigen::Matrix3d& R);

// The program as CSV: a header line, then point,layer,x_mm,y_mm,z_mm,a_deg,b_deg,c_deg,tilt_deg,rotation_deg,
// speed_mm_min,bead_height_mm,weld; without tilt_deg for a turntable cell and without both for no positioner.
std::string ProgramToCsv(const RobotProgram& program);

// A value as a program prints it with three decimals: magnitudes below 5e-4 become 0, so no "-0.000" appears.
inline double ProgramValue(double v) { return (v < 5e-4 && v > -5e-4) ? 0.0 : v; }

}  // namespace waam::planner
