// The body shared by the program readers' fuzz targets: one reader (by format), then the conversion of what it read
// into a plan on the built-in cell's kinematics, as `waam import` does. Any input may be refused with
// waam::InputError; anything else is a bug. The analysis tests replay the kept inputs through the same function.
#pragma once

#include <string>
#include <string_view>

#include "models/core/error.h"
#include "planner/program/program_plan.h"
#include "planner/program/program_reader.h"

namespace waam::fuzz {

// Reads `text` as `format` (KUKA KRL: a .src followed by its .dat, split at DEFDAT) and plans it; `file` names the
// input in messages. Returns normally or throws waam::InputError.
inline void ReadAndPlanProgram(std::string_view text, const std::string& file, planner::ProgramFormat format) {
  static const planner::CellKinematics cell = [] {
    planner::CellKinematics c;
    c.arm = planner::OpwArm::ArcMate100iC12();
    c.X_WB.translation() = Eigen::Vector3d(1050.0, 0.0, 0.0);
    return c;
  }();
  // Yaskawa pulse positions are read (not refused) with some pulses per degree.
  planner::JbiReadOptions jbi;
  jbi.robot_pulses_per_deg = {1000.0, 1400.0, 1000.0, 800.0, 1200.0, 500.0};
  jbi.station_pulses_per_deg = {1365.3, 1137.8};
  // Numbered frames and tools 1 and 2 are given, as a scenario's program.frames would (the others are refused).
  static const planner::ProgramFrames frames = [] {
    planner::ProgramFrames f;
    f.uframe[1] = {100.0, 0.0, 50.0, 0.0, 0.0, 90.0};
    f.uframe[2] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    f.utool[1] = std::array<double, 6>{0.0, 0.0, 400.0, 0.0, -20.0, 0.0};
    f.utool[2] = std::nullopt;
    return f;
  }();
  const planner::ParsedProgram program = planner::ReadProgramText(text, file, format, {}, jbi, frames);
  (void)program.MotionsByKind();
  planner::ImportSettings settings;
  settings.arc_step_mm = 5.0;
  (void)planner::ProgramToPlan(program, cell, settings);
}

}  // namespace waam::fuzz
