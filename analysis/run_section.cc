// The scenario's optional `run` section: the steps of `waam run` and the exit code a benchmark expects.
#include "analysis/run_settings.h"

#include "models/core/error.h"
#include "models/core/yaml_map.h"

namespace waam::analysis::internal {

void ParseRunSection(YamlMap& top, RunSettings* out) {
  if (!top.Has("run")) return;
  YamlMap run = top.Map("run");
  if (run.Has("steps")) out->where = run.Where("steps");
  ReadFields<RunSettings>(run, kRunFields, out);
  WAAM_THROW_UNLESS(out->expected_exit_code == 0 || out->expected_exit_code == 3,
                    run.Where("expected_exit_code") << " = " << out->expected_exit_code
                    << ": must be 0 (success) or 3 (check violations)");
  run.CheckNoUnknownKeys();
}

}  // namespace waam::analysis::internal
