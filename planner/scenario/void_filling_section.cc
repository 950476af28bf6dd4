// The `path.void_filling` scenario section: how turning points at rib-web junctions are corrected.
#include "models/core/error.h"
#include "models/core/yaml_map.h"
#include "planner/scenario/scenario_fields.h"
#include "planner/scenario/void_filling_settings.h"

namespace waam::planner::internal {

void ParseVoidFillingSection(YamlMap& path, VoidFillingSettings* out) {
  if (!path.Has("void_filling")) return;
  YamlMap map = path.Map("void_filling");
  out->where = map.Where("");
  ReadFields<VoidFillingSettings>(map, kVoidFillingFields, out);
  WAAM_THROW_UNLESS(out->mode != VoidFillingMode::kTuned || !out->tune_file.empty(),
                    map.Where("mode") << ": mode tuned needs tune_file (the tune.json of waam tune-voids)");
  map.CheckNoUnknownKeys();
}

}  // namespace waam::planner::internal
