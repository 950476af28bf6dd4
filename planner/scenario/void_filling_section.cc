// The `path.void_filling` scenario section: how turning points at rib-web junctions are corrected.
#include <system_error>

#include "models/core/error.h"
#include "planner/scenario/void_filling_settings.h"
#include "planner/scenario/yaml_fields.h"

namespace waam::planner::internal {
namespace fs = std::filesystem;

void ParseVoidFillingSection(YamlMap& path, const fs::path& scenario_dir, VoidFillingSettings* out) {
  if (!path.Has("void_filling")) return;
  YamlMap map = path.Map("void_filling");
  out->where = map.Where("");
  out->mode = map.Enum("mode", VoidFillingMode::kNone);
  out->lambda = map.Number("lambda", 0.0, 100.0, 1.0);
  out->spacing_mm = map.Number("spacing_mm", 0.0, 100.0, 0.0);
  out->min_ribs = map.Integer("min_ribs", 2, 12, 3);
  auto file = [&](const std::string& key) {
    fs::path f = map.String(key);
    if (f.is_relative()) f = scenario_dir / f;
    std::error_code ec;
    WAAM_THROW_UNLESS(fs::is_regular_file(f, ec), map.Where(key) << ": file " << f.string() << " not found");
    return f.lexically_normal();
  };
  if (map.Has("model")) out->model = file("model");
  if (map.Has("tune_file")) out->tune_file = file("tune_file");
  WAAM_THROW_UNLESS(out->mode != VoidFillingMode::kTuned || !out->tune_file.empty(),
                    map.Where("mode") << ": mode tuned needs tune_file (the tune.json of waam tune-voids)");
  map.CheckNoUnknownKeys();
}

}  // namespace waam::planner::internal
