// The scenario's optional `place` section: the ranges `waam place` searches.
#include "analysis/place_settings.h"

#include <cmath>

#include "models/core/error.h"
#include "models/core/yaml_map.h"
#include "twin/cell/cell_settings.h"

namespace waam::analysis::internal {
namespace {

// A range over the values of the cell key whose row is `cell_field`, within that key's limits.
std::optional<PlaceRange> Range(YamlMap& map, const char* key, const Field<twin::CellSettings>& cell_field) {
  if (!map.Has(key)) return std::nullopt;
  const double limit = cell_field.max;
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
  using twin::kCellPartFields, twin::kCellPositionerFields, twin::kCellRobotFields;
  using Cell = twin::CellSettings;
  const Field<Cell>& offset = FieldOf<Cell>(kCellPartFields, "offset_mm");
  const Field<Cell>& robot_base = FieldOf<Cell>(kCellRobotFields, "base_mm");
  out->part_x_mm = Range(place, "part_x_mm", offset);
  out->part_y_mm = Range(place, "part_y_mm", offset);
  out->part_z_mm = Range(place, "part_z_mm", offset);
  out->part_yaw_deg = Range(place, "part_yaw_deg", FieldOf<Cell>(kCellPartFields, "yaw_deg"));
  out->table_rotation_deg = Range(place, "table_rotation_deg", FieldOf<Cell>(kCellPositionerFields, "rotation_deg"));
  out->positioner_yaw_deg = Range(place, "positioner_yaw_deg", FieldOf<Cell>(kCellPositionerFields, "yaw_deg"));
  out->robot_x_mm = Range(place, "robot_x_mm", robot_base);
  out->robot_y_mm = Range(place, "robot_y_mm", robot_base);
  ReadFields<PlaceSettings>(place, kPlaceFields, out);
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
