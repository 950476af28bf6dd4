// The scenario: every section of a scenario file (the planner's, the twin's and the analysis's), read from one
// document, with the files it names loaded.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/place_settings.h"
#include "analysis/replay_settings.h"
#include "analysis/run_settings.h"
#include "analysis/thermal_settings.h"
#include "planner/program/program_settings.h"
#include "models/core/yaml_map.h"
#include "planner/scenario/scenario.h"
#include "twin/cell/cell_settings.h"
#include "twin/simulation_settings.h"

namespace waam::analysis {

// The one scenario type. Its planner sections are its planner::PlannerSections base, so that the planner is handed
// the scenario itself; the twin's and the analysis's sections follow.
struct Scenario : planner::PlannerSections {
  twin::CellSettings cell;              // optional `cell:` section (docs/CELL.md)
  twin::SimulationSettings simulation;  // optional `simulation:` section (the voxel twin)
  RunSettings run;                      // optional `run:` section (the steps of `waam run`)
  planner::ProgramSettings program;     // optional `program:` section: a program made elsewhere instead of a part
  PlaceSettings place;                  // optional `place:` section: the ranges `waam place` searches
  ThermalSection thermal;               // optional `thermal:` section: the thermal model (`waam thermal`)
  ReplaySection replay;                 // optional `replay:` section: a process log (`waam thermal replay`)
};

// Loads and validates a whole scenario file: the document is read once (with the `--set` overrides, "key.path=value"
// strings, checked against the field tables) and each module parses its own sections from it; a top-level key that no
// module reads is refused; then LoadScenarioFiles reads what it names. Throws InputError naming the file, line and
// key path (e.g. "s.yaml:7: slicing.layer_height_mm = -1: must be in [0.05, 20]"), or the file that cannot be read.
Scenario LoadScenario(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

// The name a scenario given as a document (ScenarioFromJson) has in messages, in the folder it was given.
inline constexpr const char* kScenarioDocumentName = "<dict>";

// Builds a scenario from a JSON document with the YAML file's structure (e.g. a Python dict), with the same checks
// and messages as LoadScenario; relative paths in it (meshes, programs, materials) are taken from `base_dir`, and
// messages name `base_dir`/<dict> and the key path (a document has no lines). Throws InputError.
Scenario ScenarioFromJson(const nlohmann::json& document, const std::filesystem::path& base_dir,
                          const std::vector<std::string>& overrides = {});

// Reads the files a scenario names into it: the part's STL bytes (part.mesh_data), the process's CSW, speed-height
// and width-height models, the void-length model and a tuned void filling's tune.json shifts, and the twin's CSW model
// (each the named file or the default in models/data). Throws InputError naming a file that is missing or malformed.
void LoadScenarioFiles(Scenario* scenario);

// A scenario file read once, with the `--set` overrides ("key.path=value") applied, as its top-level map. Throws
// InputError for a YAML syntax error (file:line) or a malformed override (naming it).
YamlMap LoadScenarioTop(const std::filesystem::path& file, const std::vector<std::string>& overrides);
// A scenario document already in memory (`root`, a mapping), with the overrides applied, as its top-level map; `file`
// names it in messages and its folder is where relative paths (meshes, programs, materials) are taken from.
// Throws InputError for a malformed override.
YamlMap ScenarioTop(YAML::Node root, const std::filesystem::path& file, const std::vector<std::string>& overrides);

}  // namespace waam::analysis
