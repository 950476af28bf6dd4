// Five-axis transform of Dai et al. 2020 sec. 3: the turntable rotation that turns a path point's tool vector to a
// target direction (the torch axis, gravity), as a 4x4 matrix about a centre point (eq. 3-5).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace waam::planner {

// Rotation angles about the fixed x, y and z axes (rad), applied z first, then y, then x: M = Rx(a) Ry(b) Rz(c).
struct AxisAngles {
  double a = 0.0;  // about x, rad
  double b = 0.0;  // about y, rad
  double c = 0.0;  // about z, rad
  bool real = true;  // false: no rotation about the chosen pair of axes turns v_s onto v_t (solution 1)
};

// Eq. 3: the homogeneous transform that rotates about the centre C_mm by Rx(a) Ry(b) Rz(c):
// M = T(C) Rx(a) Ry(b) Rz(c) T(-C).
Eigen::Matrix4d DaiTransform(const Eigen::Vector3d& C_mm, const AxisAngles& angles);

// Solution 1 (sec. 3.1, Fig. 10a): angles c about z, then a about x (b = 0) that turn the unit vector v_s onto the
// unit vector v_t; `positive_branch` picks the sign of Y_Q. real = false when X_t^2 + Z_s^2 > 1.
AxisAngles SolveDaiSolution1(const Eigen::Vector3d& v_s, const Eigen::Vector3d& v_t, bool positive_branch);

// Solution 2 (sec. 3.2, eq. 4-5): v_s to v_z(0, 0, 1) about z then x, then v_z to v_t by the inverse of the same
// construction for v_t. Always real. Returns the 3x3 rotation M_sot; `to_z` (may be null) receives the first
// step's angles (c about z, a about x), which for v_t = v_z are the turntable's rotation and tilt.
Eigen::Matrix3d SolveDaiSolution2(const Eigen::Vector3d& v_s, const Eigen::Vector3d& v_t, AxisAngles* to_z);

}  // namespace waam::planner
