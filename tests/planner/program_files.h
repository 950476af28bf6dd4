// The program reader tests' file reading: a fixture file read and handed to the planner's readers, as
// analysis::ReadProgramFile does for the CLI (a KRL .src with the .dat beside it).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "models/core/files.h"
#include "planner/program/program_plan.h"
#include "planner/program/program_reader.h"

namespace waam::planner::testing {

// Reads the fixture `path` with the reader of `format` (empty: detected); a KRL .src with its .dat when there is one.
inline ParsedProgram ReadProgramFile(const std::filesystem::path& path, std::optional<ProgramFormat> format,
                                     const GcodeReadOptions& gcode = {}, const JbiReadOptions& jbi = {},
                                     const ProgramFrames& frames = {}) {
  const std::string text = ReadFile(path);
  const ProgramFormat f = format ? *format : DetectProgramFormat(path, text);
  ParsedProgram program;
  if (f == ProgramFormat::kKukaKrl) {
    std::filesystem::path dat = path;
    dat.replace_extension(".dat");
    const std::string dat_text = std::filesystem::is_regular_file(dat) ? ReadFile(dat) : "";
    program = ReadKukaKrl(text, dat_text, path.string(), dat.string(), frames);
  } else {
    program = ReadProgramText(text, path.string(), f, gcode, jbi, frames);
  }
  if (program.name.empty()) program.name = path.stem().string();
  return program;
}

// The FANUC ARC Mate 100iC/12 cell the reader tests plan programs on: the torch 400 mm along the flange, pointing
// along the flange's x, the robot base 1050 mm from the world origin.
inline CellKinematics ProgramTestCell() {
  CellKinematics cell;
  cell.arm = OpwArm::ArcMate100iC12();
  cell.X_FT.translation() = Eigen::Vector3d(400.0, 0.0, 0.0);
  cell.X_FT.linear() << 0, 0, 1, 0, -1, 0, 1, 0, 0;
  cell.X_WB.translation() = Eigen::Vector3d(1050.0, 0.0, 0.0);
  return cell;
}

// The first warning of `program` whose text contains `text`, or null.
inline const ProgramWarning* FindProgramWarning(const ParsedProgram& program, const std::string& text) {
  for (const ProgramWarning& w : program.warnings) {
    if (w.what.find(text) != std::string::npos) return &w;
  }
  return nullptr;
}

}  // namespace waam::planner::testing
