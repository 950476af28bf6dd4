// A whole scenario file: the planner's sections and those the twin and the analysis own, read from one document.
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
#include "planner/scenario/scenario.h"
#include "twin/cell/cell_settings.h"
#include "twin/simulation_settings.h"

namespace waam::analysis {

struct Scenario : planner::Scenario {
  twin::CellSettings cell;              // optional `cell:` section (docs/CELL.md)
  twin::SimulationSettings simulation;  // optional `simulation:` section (the voxel twin)
  RunSettings run;                      // optional `run:` section (the steps of `waam run`)
  planner::ProgramSettings program;     // optional `program:` section: a program made elsewhere instead of a part
  PlaceSettings place;                  // optional `place:` section: the ranges `waam place` searches
  ThermalSection thermal;               // optional `thermal:` section: the thermal model (`waam thermal`)
  ReplaySection replay;                 // optional `replay:` section: a process log (`waam thermal replay`)
};

// Loads and validates a whole scenario file: the document is read once (with the `--set` overrides) and each module
// parses its own sections from it; a top-level key that no module reads is refused. Throws InputError naming the
// file, line and key path, as planner::LoadScenario does.
Scenario LoadScenario(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

// The name a scenario given as a document (ScenarioFromJson) has in messages, in the folder it was given.
inline constexpr const char* kScenarioDocumentName = "<dict>";

// Builds a scenario from a JSON document with the YAML file's structure (e.g. a Python dict), with the same checks
// and messages as LoadScenario; relative paths in it (meshes, programs, materials) are taken from `base_dir`, and
// messages name `base_dir`/<dict> and the key path (a document has no lines). Throws InputError.
Scenario ScenarioFromJson(const nlohmann::json& document, const std::filesystem::path& base_dir,
                          const std::vector<std::string>& overrides = {});

}  // namespace waam::analysis
