// The `path.void_filling` scenario section: how turning points at rib-web junctions are corrected.
#include "models/core/error.h"
#include "models/core/yaml_map.h"
#include "planner/scenario/scenario_fields.h"
#include "planner/scenario/void_filling_settings.h"

namespace waam::planner::internal {
namespace fs = std::filesystem;

void ParseVoidFillingSection(YamlMap& path, const fs::path& scenario_dir, VoidFillingSettings* out) {
  if (!path.Has("void_filling")) return;
  YamlMap map = path.Map("void_filling");
  out->where = map.Where("");
  ReadFields<VoidFillingSettings>(map, kVoidFillingFields, out);
  if (map.Has("model")) out->model = map.File("model", scenario_dir, "file");
  if (map.Has("tune_file")) out->tune_file = map.File("tune_file", scenario_dir, "file");
  WAAM_THROW_UNLESS(out->mode != VoidFillingMode::kTuned || !out->tune_file.empty(),
                    map.Where("mode") << ": mode tuned needs tune_file (the tune.json of waam tune-voids)");
  map.CheckNoUnknownKeys();
}

}  // namespace waam::planner::internal
