// Reading a robot program or G-code file: the file (and a KRL program's companion) read here, parsed by the
// planner's reader of its dialect.
#pragma once

#include <filesystem>
#include <optional>

#include "planner/program/program_reader.h"

namespace waam::analysis {

// Reads `path` (at most planner::kMaxProgramBytes, checked before reading) with the reader of `format` (empty:
// detected from the extension or the first lines); a KRL .src is read with the .dat beside it (same name), a .dat
// with its .src. Throws InputError naming the file when it cannot be read or is too large, and as the reader does.
planner::ParsedProgram ReadProgramFile(const std::filesystem::path& path, std::optional<planner::ProgramFormat> format,
                                       const planner::GcodeReadOptions& gcode = {},
                                       const planner::JbiReadOptions& jbi = {},
                                       const planner::ProgramFrames& frames = {});

}  // namespace waam::analysis
