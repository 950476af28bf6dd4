// The scenario's optional `place` section: the ranges `waam place` searches.
#include "analysis/place_settings.h"

#include <cmath>

#include "models/core/error.h"
#include "models/core/yaml_map.h"
#include "twin/cell/cell_settings.h"

namespace waam::analysis::internal {
namespace {

// The range's values; more than kMaxPlaceLayouts counts as kMaxPlaceLayouts + 1 (the count of a step of 1e-300
// fits no integer type).
std::size_t Count(const std::optional<PlaceRange>& r) {
  if (!r || r->step <= 0.0) return 1;
  const double n = std::floor((r->max - r->min) / r->step + 1e-9) + 1.0;
  if (!(n <= static_cast<double>(kMaxPlaceLayouts))) return kMaxPlaceLayouts + 1;
  return static_cast<std::size_t>(n);
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
  ReadFields<PlaceSettings>(place, kPlaceFields, out);
  place.CheckNoUnknownKeys();
  CheckPlaceLayouts(*out, out->where);
}

}  // namespace waam::analysis::internal

namespace waam::analysis {

void CheckPlaceLayouts(const PlaceSettings& place, const std::string& where) {
  std::size_t layouts = 1;
  for (const auto* r : {&place.part_x_mm, &place.part_y_mm, &place.part_z_mm, &place.part_yaw_deg,
                        &place.table_rotation_deg, &place.positioner_yaw_deg, &place.robot_x_mm, &place.robot_y_mm}) {
    layouts *= internal::Count(*r);
    WAAM_THROW_UNLESS(layouts <= kMaxPlaceLayouts, where << ": the ranges give more than " << kMaxPlaceLayouts
                                                         << " layouts; use larger steps or fewer ranges");
  }
}

}  // namespace waam::analysis
