// A scenario file as a YAML document: read once with the `--set` overrides, and the planner's sections parsed from it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "models/core/yaml_map.h"
#include "planner/scenario/scenario.h"

namespace waam::planner {

// A scenario file read once, with the `--set` overrides ("key.path=value") applied, as its top-level map. Throws
// InputError for a YAML syntax error (file:line) or a malformed override (naming it).
YamlMap LoadScenarioTop(const std::filesystem::path& file, const std::vector<std::string>& overrides);
// A scenario document already in memory (`root`, a mapping), with the overrides applied, as its top-level map; `file`
// names it in messages and its folder is where relative paths (meshes, programs, materials) are taken from.
// Throws InputError for a malformed override or a root that is not a mapping.
YamlMap ScenarioTop(YAML::Node root, const std::filesystem::path& file, const std::vector<std::string>& overrides);
// The planner's sections of a scenario file's top-level map (the sections every module reads from the same map).
// Throws InputError naming file:line and key.
Scenario ParsePlannerSections(YamlMap& top);

}  // namespace waam::planner
