// Parser of the scenario's optional `cell:` section (internal: it exposes yaml-cpp through YamlMap).
#pragma once

#include <filesystem>

#include "planner/scenario/yaml_fields.h"
#include "twin/cell/cell_settings.h"

namespace waam::twin::internal {
using planner::internal::YamlMap;

// Reads `cell:` from the scenario's top-level map (defaults when absent); relative `mjcf` paths are resolved against
// `scenario_dir`. Throws InputError naming file:line and the key for a wrong type, range or unknown key, or a
// missing MJCF file.
CellSettings ParseCellSection(YamlMap& top, const std::filesystem::path& scenario_dir);

}  // namespace waam::twin::internal
