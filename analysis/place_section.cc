// The scenario's optional `place` section: the ranges `waam place` searches.
#include "analysis/place_settings.h"

#include <cmath>

#include "models/core/error.h"
#include "planner/scenario/yaml_fields.h"

namespace waam::analysis::internal {
namespace {

std::optional<PlaceRange> Range(YamlMap& map, const char* key, double limit) {
  if (!map.Has(key)) return std::nullopt;
  const YAML::Node node = map.node()[key];
  PlaceRange r;
  if (node.IsScalar()) {
    r.min = r.max = map.Number(key, -limit, limit);
    return r;
  }
  const std::vector<double> v = map.Numbers(key, 3, -limit, limit);
  r = {v[0], v[1], v[2]};
  WAAM_THROW_UNLESS(r.min <= r.max, map.Where(key) << " = [" << r.min << ", " << r.max << ", " << r.step
                                                   << "]: min must not exceed max ([min, max, step])");
  WAAM_THROW_UNLESS(r.step >= 0.0, map.Where(key) << ": step " << r.step << " must not be negative");
  WAAM_THROW_UNLESS(r.step > 0.0 || r.min == r.max,
                    map.Where(key) << ": step 0 with min < max; give a step, or one number for a single value");
  return r;
}

std::size_t Count(const std::optional<PlaceRange>& r) {
  if (!r || r->step <= 0.0) return 1;
  return static_cast<std::size_t>(std::floor((r->max - r->min) / r->step + 1e-9)) + 1;
}

}  // namespace

void ParsePlaceSection(YamlMap& top, PlaceSettings* out) {
  if (!top.Has("place")) {
    out->part_x_mm = out->part_y_mm = kDefaultPartXy;
    out->part_yaw_deg = kDefaultPartYaw;
    return;
  }
  YamlMap place = top.Map("place");
  out->where = place.Where("");
  out->part_x_mm = Range(place, "part_x_mm", 20000.0);
  out->part_y_mm = Range(place, "part_y_mm", 20000.0);
  out->part_z_mm = Range(place, "part_z_mm", 20000.0);
  out->part_yaw_deg = Range(place, "part_yaw_deg", 360.0);
  out->table_rotation_deg = Range(place, "table_rotation_deg", 240.0);
  out->positioner_yaw_deg = Range(place, "positioner_yaw_deg", 360.0);
  out->robot_x_mm = Range(place, "robot_x_mm", 20000.0);
  out->robot_y_mm = Range(place, "robot_y_mm", 20000.0);
  out->coarse_layers = place.Integer("coarse_layers", 2, 100000, out->coarse_layers);
  out->coarse_step_mm = place.Number("coarse_step_mm", 0.1, 100.0, out->coarse_step_mm);
  out->finalists = place.Integer("finalists", 1, 1000, out->finalists);
  place.CheckNoUnknownKeys();
  std::size_t layouts = 1;
  for (const auto* r : {&out->part_x_mm, &out->part_y_mm, &out->part_z_mm, &out->part_yaw_deg,
                        &out->table_rotation_deg, &out->positioner_yaw_deg, &out->robot_x_mm, &out->robot_y_mm}) {
    layouts *= Count(*r);
    WAAM_THROW_UNLESS(layouts <= kMaxPlaceLayouts, out->where << ": the ranges give more than " << kMaxPlaceLayouts
                                                              << " layouts; use larger steps or fewer ranges");
  }
}

}  // namespace waam::analysis::internal
