// ABB RAPID writer: one module with robtargets (quaternions, confdata from the IK branch, the positioner as external
// axes), the arc welding instructions ArcLStart / ArcL / ArcLEnd and their welddata.
#pragma once

#include <string>

#include <Eigen/Geometry>

#include "planner/program/robot_program.h"

namespace waam::planner {

struct AbbRapidOptions {
  // The work object the positions are written in (wobjdata uframe), in the robot base frame R, mm: by default the
  // frame BuildProgram writes positions in (R lifted to the j2 axis).
  Eigen::Isometry3d X_RU = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_FT = Eigen::Isometry3d::Identity();  // the torch TCP on the flange (twin convention), mm
};

// The .mod text: MODULE <name> with tooldata tWAAM, wobjdata wobjWAAM, seamdata, one welddata per weld speed
// (weld_speed mm/s), one speeddata per travel speed, one CONST robtarget per point ([[x,y,z],[q1..q4],[cf1,cf4,cf6,
// cfx],[tilt,rotation,9E+09 x4]]), and PROC main: MoveJ to the first point, MoveL for travel, ArcLStart on the point
// where a pass starts, ArcL along it, ArcLEnd at its last point. cfx = 4 (shoulder back) + 2 (elbow down) + 1 (wrist
// flipped). Deterministic.
std::string ProgramToAbbRapid(const RobotProgram& program, const AbbRapidOptions& options);

}  // namespace waam::planner
