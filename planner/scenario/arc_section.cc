// The `process.arc` and `process.interpass` scenario keys: the arc's power and efficiency, and the interpass rule.
#include <cmath>
#include <string_view>

#include "models/core/error.h"
#include "models/core/yaml_map.h"
#include "planner/scenario/arc_settings.h"

namespace waam::planner {

namespace {

void ParseArc(YamlMap& process, ArcSettings* arc) {
  if (!process.Has("arc")) return;
  YamlMap map = process.Map("arc");
  arc->given = true;
  arc->where = map.Where("");
  const bool power = map.Has("power_w");
  const bool electrical = map.Has("voltage_v") || map.Has("current_a");
  WAAM_THROW_UNLESS(power || electrical, arc->where << ": the arc has no power: give power_w (W), or voltage_v (V) "
                                                       "and current_a (A)");
  WAAM_THROW_UNLESS(!(power && electrical), map.Where("power_w") << ": give power_w, or voltage_v and current_a, "
                                                                    "not both");
  auto read = [&](std::string_view key) { ReadField<ArcSettings>(map, kArcFields, key, arc); };
  if (power) {
    read("power_w");
  } else {
    WAAM_THROW_UNLESS(map.Has("voltage_v") && map.Has("current_a"),
                      arc->where << ": the arc has no power: give both voltage_v (V) and current_a (A), or power_w");
    read("voltage_v");
    read("current_a");
    arc->power_w = arc->voltage_v * arc->current_a;
  }
  read("efficiency");
  map.CheckNoUnknownKeys();
}

void ParseInterpass(YamlMap& process, InterpassSettings* interpass) {
  if (!process.Has("interpass")) return;
  YamlMap map = process.Map("interpass");
  interpass->where = map.Where("");
  if (map.Has("max_c")) {
    interpass->max_where = map.Where("max_c");
    ReadField<InterpassSettings>(map, kInterpassFields, "max_c", interpass);
  }
  if (map.Has("at")) {
    interpass->at_where = map.Where("at");
    ReadField<InterpassSettings>(map, kInterpassFields, "at", interpass);
    WAAM_THROW_UNLESS(interpass->HasMax(), interpass->at_where << ": says where max_c is measured, but "
                                                                  "process.interpass has no max_c");
  }
  ReadField<InterpassSettings>(map, kInterpassFields, "min_layer_time_s", interpass);
  map.CheckNoUnknownKeys();
}

}  // namespace

void ParseArcAndInterpass(YamlMap& process, ArcSettings* arc, InterpassSettings* interpass) {
  ParseArc(process, arc);
  ParseInterpass(process, interpass);
}

void ValidateArcAndInterpass(const ArcSettings& arc, const InterpassSettings& interpass) {
  CheckFields<ArcSettings>(kArcFields, arc, "process.arc");
  WAAM_THROW_UNLESS(!arc.given || !std::isnan(arc.power_w),
                    arc.where << ": the arc has no power: give power_w (W), or voltage_v (V) and current_a (A)");
  CheckFields<InterpassSettings>(kInterpassFields, interpass, "process.interpass");
}

}  // namespace waam::planner
