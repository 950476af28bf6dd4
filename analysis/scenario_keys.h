// Every key of a scenario, from the field tables of each module's sections (models/core/field_table.h): the key
// paths `--set` and a sweep may name, the generated key tables of docs/SCENARIO_KEYS.md, and the validation of a
// scenario built or changed in code.
#pragma once

#include <string>
#include <vector>

#include "analysis/scenario.h"
#include "models/core/field_table.h"

namespace waam::analysis {

// One section: its dotted path ("" for the top level, "cell.torch") and its keys in table order; a section whose keys
// depend on its type (part.generator) has one SectionKeys per type, named by `variant`.
struct SectionKeys {
  std::string path;
  std::vector<FieldInfo> fields;
  std::string variant = {};
};

// Every section of a scenario, in the order of docs/SCENARIO_KEYS.md.
const std::vector<SectionKeys>& ScenarioSections();

// True if `key_path` ("path.bead_width_mm", "part.generator.height_mm") names a key of a section (of any type's, for
// part.generator), a section, or a key under a mapping or list (program.frames.uframe.6, slicing.sub_volumes).
bool IsScenarioKeyPath(const std::string& key_path);

// Throws InputError "--set 'k=v': unknown key 'k' (keys of <section>: ...)" for an override whose key path no
// section has (a malformed override is left to the loader's message).
void CheckOverrideKeys(const std::vector<std::string>& overrides);

// The key tables of docs/SCENARIO_KEYS.md, generated from the field tables (`waam scenario-keys`).
std::string ScenarioKeysMarkdown();

// Throws InputError "<section>.<key> = value: must be in [min, max]" (or the rule a list, a keyed map or a generator
// parameter breaks) for a value outside what its scenario key allows, in any section, the cell's included: the check
// of a scenario built or changed in code (waam place, an API), also run by the loader on every scenario it hands out.
void ValidateScenario(const Scenario& scenario);

}  // namespace waam::analysis
