// Coordinated eight-axis motion of the cell along a planned path: positioner angles per layer, torch pose per
// point, arm joints by closed-form IK with the branch kept continuous, and time stamps at the planned speeds.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "planner/kinematics/opw_arm.h"
#include "planner/kinematics/positioner.h"
#include "planner/path/tool_path.h"

namespace waam::planner {

using Joints8 = Eigen::Matrix<double, 8, 1>;  // j1..j6 of the arm, positioner tilt, positioner rotation; rad

// Numerical inverse kinematics for arms the closed form does not cover: flange pose X_RF (mm) and a seed (rad) in,
// joints out; returns false (with the remaining pose error in mm) when it did not converge.
using NumericIk = std::function<bool(const Eigen::Isometry3d& X_RF, const Joints6& seed, Joints6* q,
                                     double* residual_mm)>;

// The cell's kinematics in the world frame W (floor, z up): arm base R, tool, positioner base B, part P.
struct CellKinematics {
  OpwArm arm;          // limits and speeds always; the OPW geometry only when numeric_ik is empty
  NumericIk numeric_ik;  // set for a user's arm that is not of the OPW kind: used instead of the closed form
  Eigen::Isometry3d X_WR = Eigen::Isometry3d::Identity();  // arm base in W, mm
  Eigen::Isometry3d X_FT = Eigen::Isometry3d::Identity();  // TCP in the flange frame, mm; z_T points into the work
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();  // positioner base in W, mm
  Positioner positioner;                                   // includes the part frame on the table
};

// Torch pose in W for a TCP at p_W (mm) with the torch axis `tool_dir_W` (unit, from the TCP up the torch):
// z_T = -tool_dir_W, and x_T points away from the arm's j1 axis (so j6 stays put as the arm swings).
// `spin_rad` turns x_T (and y_T) further about z_T: the torch's rotation about its own axis, which the weld does not
// see and the redundancy resolution chooses (twin/cell/cell_resolve.h).
Eigen::Isometry3d TorchPose(const CellKinematics& cell, const Eigen::Vector3d& p_W, const Eigen::Vector3d& tool_dir_W,
                            double spin_rad = 0.0);

// One checked point of the motion: a path point or a point inserted between two (at most step_mm apart).
struct CellSample {
  int layer = 0;
  int point = 0;            // index of the path point the move ends at, counted over the whole plan
  bool weld = false;        // the move to this sample deposits metal
  double t_s = 0.0;         // time since the start, s
  double dt_s = 0.0;        // time from the previous sample, s
  Eigen::Vector3d p_P = Eigen::Vector3d::Zero();  // TCP in the part frame, mm
  double bead_width_mm = 0.0;
  double bead_height_mm = 0.0;
  double speed_mm_s = 0.0;  // TCP speed relative to the part, mm/s
  Joints8 q = Joints8::Zero();
  bool reachable = true;
  double reach_excess_mm = 0.0;  // when unreachable: how far the wrist centre lies outside the arm's shell, mm
                                 // (numerical IK: the pose error it could not remove, mm)
  bool arm_within_limits = true; // a closed-form branch within all joint limits exists
  int branch = 0;                // IkSolution::branch of the chosen solution
  bool positioner_at_limit = false;
  double torch_tilt_rad = 0.0;   // angle between the torch axis and vertical, rad
  Eigen::Isometry3d X_WT = Eigen::Isometry3d::Identity();  // torch pose in W, mm
};

struct MotionOptions {
  double step_mm = 1.0;            // > 0: longest distance between samples along a move, mm
  double rapid_speed_mm_s = 100.0; // > 0: TCP speed of arc-off moves, mm/s
  double rotation_rad = 0.0;       // table rotation while the build direction is vertical, rad
  // false: positioner angles per layer from the layer's build direction; true: per sample from the point's tool
  // direction (curved layers: the positioner keeps turning the local normal up while welding).
  bool positioner_per_point = false;
  // The process's tolerance on the torch angle to gravity: > 0 lets the positioner stop short of turning the build
  // direction exactly up (SolvePositionerAnglesWithin), rad.
  double tilt_tolerance_rad = 0.0;
  // Per layer (index into plan.layers): the torch's spin about its axis, rad (empty: 0 everywhere). It changes from
  // the last layer's value to the layer's own over the move into the layer (an arc-off move), or over the whole layer
  // when it is entered by a weld move (a spiral), as the positioner's angles do.
  std::vector<double> layer_spin_rad;
};

// Samples the plan's moves, solves positioner angles (per layer, from the layer's build direction, interpolated
// over the travel move into the layer; or per sample, see MotionOptions) and arm joints (nearest branch to the previous sample) and time-stamps the
// samples: weld moves at the planned speed, arc-off moves at the rapid speed but never faster than any axis allows.
// The torch poses are computed in parallel, the IK and time stamps in order (each depends on the previous sample);
// the result does not depend on the thread count. `progress` (may be empty) is called with the number of samples
// done. A point with its own positioner angles (PathPoint::positioner_rad, a program made elsewhere) is reached with
// those, linearly along its move, instead of solved ones.
std::vector<CellSample> PlanCellMotion(const CellKinematics& cell, const Plan& plan, const MotionOptions& options,
                                       const std::function<void(std::size_t)>& progress);

// Number of samples PlanCellMotion will produce (for progress bars and benchmarks).
std::size_t CountCellSamples(const Plan& plan, double step_mm);

}  // namespace waam::planner
