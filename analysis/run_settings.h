// What `waam run` does with a scenario (optional scenario section `run`): its steps and the exit code it expects.
#pragma once

#include <string>
#include <vector>

#include "models/core/field_table.h"

namespace waam::analysis {

struct RunSettings {
  // Steps in order (names registered by analysis/run_steps.cc: plan, check, simulate, ...). Empty = the default
  // chain: plan, check, simulate, then every optional step whose own scenario section is present.
  std::vector<std::string> steps;
  // The exit code `waam run` is expected to end with: 0, or 3 for a planted cell fault that `check` must find.
  // `waam bench` reports a scenario that ends as expected with a non-zero code as "expected_fail".
  int expected_exit_code = 0;
  std::string where;                 // "file:line: run.steps" for messages about the steps (empty if absent)
};

// The `run:` section, one row per key (models/core/field_table.h).
inline constexpr std::array kRunFields = {
    WordsField<&RunSettings::steps>("steps", "step", 0, "steps in order (waam run --help); absent: the default chain"),
    NumField<&RunSettings::expected_exit_code>("expected_exit_code", "", 0, 3, "0, or 3 for a planted cell fault"),
};

}  // namespace waam::analysis

namespace waam::analysis::internal {
// Reads the optional `run:` mapping of the scenario's top level into `out`. Step names are checked by the analysis
// layer (which knows the registered steps); here only types and the exit code range (0 or 3). Throws InputError.
void ParseRunSection(YamlMap& top, RunSettings* out);
}  // namespace waam::analysis::internal
