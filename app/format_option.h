// The --format option shared by `waam import` and `waam export`: a program dialect by name, or auto.
#pragma once

#include <optional>
#include <string>

#include "planner/program/program_motion.h"

namespace waam::app {

// nullopt for "auto" (the caller picks the dialect from the file), else the named dialect. Throws InputError naming
// the option and the names it accepts.
std::optional<planner::ProgramFormat> ProgramFormatOption(const std::string& text);

}  // namespace waam::app
