// The `process.arc` and `process.interpass` scenario keys: the arc's power and efficiency, and the interpass rule.
#include "models/core/error.h"
#include "planner/scenario/arc_settings.h"
#include "models/core/yaml_map.h"

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
  if (power) {
    arc->power_w = map.Number("power_w", 1.0, 1.0e6);
  } else {
    WAAM_THROW_UNLESS(map.Has("voltage_v") && map.Has("current_a"),
                      arc->where << ": the arc has no power: give both voltage_v (V) and current_a (A), or power_w");
    arc->voltage_v = map.Number("voltage_v", 1.0, 200.0);
    arc->current_a = map.Number("current_a", 1.0, 2000.0);
    arc->power_w = arc->voltage_v * arc->current_a;
  }
  arc->efficiency = map.Number("efficiency", 0.05, 1.0, arc->efficiency);
  map.CheckNoUnknownKeys();
}

void ParseInterpass(YamlMap& process, InterpassSettings* interpass) {
  if (!process.Has("interpass")) return;
  YamlMap map = process.Map("interpass");
  interpass->where = map.Where("");
  if (map.Has("max_c")) {
    interpass->max_where = map.Where("max_c");
    interpass->max_c = map.Number("max_c", -273.15, 3000.0);
  }
  if (map.Has("at")) {
    interpass->at_where = map.Where("at");
    if (map.node()["at"].IsMap()) {
      // at: {probe: NAME}
      YamlMap at = map.Map("at");
      interpass->at = InterpassAt::kProbe;
      interpass->probe = at.String("probe");
      WAAM_THROW_UNLESS(!interpass->probe.empty(), at.Where("probe") << ": name one of thermal.probes");
      at.CheckNoUnknownKeys();
    } else {
      interpass->at = map.Enum<InterpassAt>("at");
      WAAM_THROW_UNLESS(interpass->at != InterpassAt::kProbe,
                        interpass->at_where << " = probe: name the probe, as at: {probe: NAME}");
    }
    WAAM_THROW_UNLESS(interpass->HasMax(), interpass->at_where << ": says where max_c is measured, but "
                                                                  "process.interpass has no max_c");
  }
  interpass->min_layer_time_s = map.Number("min_layer_time_s", 0.0, 86400.0, 0.0);
  map.CheckNoUnknownKeys();
}

}  // namespace

void ParseArcAndInterpass(YamlMap& process, ArcSettings* arc, InterpassSettings* interpass) {
  ParseArc(process, arc);
  ParseInterpass(process, interpass);
}

}  // namespace waam::planner
