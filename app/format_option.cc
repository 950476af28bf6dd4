// The --format option shared by `waam import` and `waam export`.
#include "app/format_option.h"

#include "models/core/error.h"

namespace waam::app {

std::optional<planner::ProgramFormat> ProgramFormatOption(const std::string& text) {
  if (text == "auto") return std::nullopt;
  const auto format = ParseEnum<planner::ProgramFormat>(text);
  WAAM_THROW_UNLESS(format.has_value(),
                    "--format " << text << ": must be auto or one of " << EnumNameList<planner::ProgramFormat>(", "));
  return format;
}

}  // namespace waam::app
