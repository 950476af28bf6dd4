// A program as read, turned into the twin's plan: every target into the part frame through the cell's kinematics
// (user frame, arm forward kinematics, positioner angles), circular moves discretised, passes grouped into layers.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "planner/kinematics/cell_motion.h"
#include "planner/path/tool_path.h"
#include "planner/program/program_motion.h"

namespace waam::planner {

struct ImportSettings {
  // The user frame U of kUser targets in the world, mm; empty = the cell's FANUC world frame (ProgramUserFrame).
  std::optional<Eigen::Isometry3d> X_WU;
  double bead_width_mm = 6.0;        // > 0: given to every point (the process decides the bead, not the program)
  double bead_height_mm = 1.5;       // > 0
  double weld_speed_mm_s = 400.0 / 60.0;  // a weld move whose program gives no speed, mm/s
  double rapid_speed_mm_s = 100.0;   // an arc-off move whose program gives no speed, mm/s
  double arc_step_mm = 1.0;          // > 0: circular moves are cut into chords at most this long, mm
  // Passes whose mean height along their build direction differs by more than this start a new layer, mm;
  // <= 0: half the bead height.
  double layer_tolerance_mm = 0.0;
};

// One target of the program resolved into the world and the part frame (before arcs are discretised).
struct ResolvedTarget {
  MotionKind kind = MotionKind::kLinear;
  int line = 0;
  Eigen::Isometry3d X_WT = Eigen::Isometry3d::Identity();  // torch pose in W, mm
  Eigen::Vector3d p_P = Eigen::Vector3d::Zero();            // TCP in the part frame, mm
  Eigen::Vector3d tool_dir_P = Eigen::Vector3d::UnitZ();    // unit, from the TCP up the torch
  double tilt_rad = 0.0;
  double rotation_rad = 0.0;
  bool missing_axis = false;  // the program moves a positioner axis the cell lacks (the value is not used)
  double speed_mm_s = 0.0;                                  // as the program gives it (<= 0: none)
  bool weld = false;
  double dwell_s = 0.0;                                     // the program's wait at the target, s
};

// The motion whose tool the check moves: the first welded one that names a tool, else the first that does; null
// when none does (the cell's torch).
const ProgramMotion* ProgramTool(const ParsedProgram& program);

// The world and part-frame pose of every motion's target, with the positioner angles in force (a motion without
// them keeps the last ones; 0, 0 before the first). Joint targets go through forward kinematics with the check's
// tool (ProgramTool, else the cell's torch). Numbered external axes go to the cell's axes in order; an axis
// the cell lacks (cell.positioner.type) stays at 0.
std::vector<ResolvedTarget> ResolveTargets(const ParsedProgram& program, const CellKinematics& cell,
                                           const ImportSettings& settings);

// The imported plan and what the conversion itself noted.
struct ImportedPlan {
  Plan plan;
  std::vector<ProgramWarning> warnings;   // the reader's, then the conversion's (unknown speeds, flat arcs)
  std::size_t points = 0;                 // path points over all layers
};

// The program as the twin's plan (part frame P). Passes (arc-off lead-in + welded run) whose mean height along
// their mean tool direction stays within the tolerance form one layer. Every point carries the program's positioner
// angles (PathPoint::positioner_rad; 0, 0 until the program first gives them), which the cell motion then follows,
// and its wait (PathPoint::dwell_s). The plan's tool (Plan::X_FT) is the program's first (a second one is warned).
// Throws InputError for a program without motions.
ImportedPlan ProgramToPlan(const ParsedProgram& program, const CellKinematics& cell, const ImportSettings& settings);

}  // namespace waam::planner
