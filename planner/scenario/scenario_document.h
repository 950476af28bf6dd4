// The planner's sections parsed from a scenario document (read, with its `--set` overrides, by analysis/scenario.h).
#pragma once

#include <filesystem>

#include "models/core/yaml_map.h"
#include "planner/scenario/scenario.h"

namespace waam::planner {

// The planner's sections (name, base_dir, part, slicing, path, process) of a scenario file's top-level map (the map
// every module reads its sections from); files are resolved and checked to exist, not read. Throws InputError naming
// file:line and key (e.g. "s.yaml:7: slicing.layer_height_mm = -1: must be in [0.05, 20]").
PlannerSections ParsePlannerSections(YamlMap& top);

}  // namespace waam::planner
