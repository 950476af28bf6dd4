// Parser of the scenario's optional `cell:` section .
#pragma once

#include <filesystem>

#include "models/core/yaml_map.h"
#include "twin/cell/cell_settings.h"

namespace waam::twin {

// Reads `cell:` from the scenario's top-level map (defaults when absent); relative file paths are resolved against
// top.base_dir(). Throws InputError naming file:line and the key for a wrong type, range or unknown key, or a
// missing MJCF file.
CellSettings ParseCellSection(YamlMap& top);

}  // namespace waam::twin
