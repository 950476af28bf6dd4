// The ranges `waam place` searches (optional scenario section `place`): where the part stands on the plate, the
// table's home rotation, the positioner's yaw and the arm's base position, and how hard to look.
#pragma once

#include <optional>
#include <string>

#include "models/core/field_table.h"
#include "twin/cell/cell_settings.h"

namespace waam::analysis {

// Values min, min + step, ... up to max (inclusive); one value when step is 0 or min == max.
struct PlaceRange {
  double min = 0.0;
  double max = 0.0;
  double step = 0.0;
};

struct PlaceSettings {
  // Each range is absolute (the value of the cell key it names); absent: the scenario's own value, not searched.
  // Without a `place` section the part's offset on the plate (x, y) and its yaw are searched over kDefault* below.
  std::optional<PlaceRange> part_x_mm;            // cell.part.offset_mm[0]
  std::optional<PlaceRange> part_y_mm;            // cell.part.offset_mm[1]
  std::optional<PlaceRange> part_z_mm;            // cell.part.offset_mm[2] (a riser under the part)
  std::optional<PlaceRange> part_yaw_deg;         // cell.part.yaw_deg
  std::optional<PlaceRange> table_rotation_deg;   // cell.positioner.rotation_deg
  std::optional<PlaceRange> positioner_yaw_deg;   // cell.positioner.yaw_deg
  std::optional<PlaceRange> robot_x_mm;           // cell.robot.base_mm[0]
  std::optional<PlaceRange> robot_y_mm;           // cell.robot.base_mm[1]
  int coarse_layers = 24;      // the coarse pass checks this many layers spread over the build (all when fewer)
  double coarse_step_mm = 5.0; // ... sampled at this spacing (the finalists at cell.checks.step_mm)
  int finalists = 4;           // layouts that get the full check, best of the coarse pass first
  std::string where;           // "file:line: place" (empty when the section is absent)
};

inline constexpr PlaceRange kDefaultPartXy{-40.0, 40.0, 20.0};
inline constexpr PlaceRange kDefaultPartYaw{0.0, 315.0, 45.0};
// The `place:` section, one row per key (models/core/field_table.h). Each range's limits are those of the cell key
// it searches (twin/cell/cell_settings.h).
inline constexpr std::array kPlaceFields = {
    RangeField<&PlaceSettings::part_x_mm>("part_x_mm", RowOf(twin::kCellPartFields, "offset_mm"),
                                          "[min, max, step] or one value of cell.part.offset_mm[0]"),
    RangeField<&PlaceSettings::part_y_mm>("part_y_mm", RowOf(twin::kCellPartFields, "offset_mm"),
                                          "... of cell.part.offset_mm[1]"),
    RangeField<&PlaceSettings::part_z_mm>("part_z_mm", RowOf(twin::kCellPartFields, "offset_mm"),
                                          "... of cell.part.offset_mm[2] (a riser)"),
    RangeField<&PlaceSettings::part_yaw_deg>("part_yaw_deg", RowOf(twin::kCellPartFields, "yaw_deg"),
                                             "... of cell.part.yaw_deg"),
    RangeField<&PlaceSettings::table_rotation_deg>("table_rotation_deg",
                                                   RowOf(twin::kCellPositionerFields, "rotation_deg"),
                                                   "... of cell.positioner.rotation_deg"),
    RangeField<&PlaceSettings::positioner_yaw_deg>("positioner_yaw_deg", RowOf(twin::kCellPositionerFields, "yaw_deg"),
                                                   "... of cell.positioner.yaw_deg"),
    RangeField<&PlaceSettings::robot_x_mm>("robot_x_mm", RowOf(twin::kCellRobotFields, "base_mm"),
                                           "... of cell.robot.base_mm[0]"),
    RangeField<&PlaceSettings::robot_y_mm>("robot_y_mm", RowOf(twin::kCellRobotFields, "base_mm"),
                                           "... of cell.robot.base_mm[1]"),
    NumField<&PlaceSettings::coarse_layers>("coarse_layers", "", 2, 100000, "layers the coarse pass checks"),
    NumField<&PlaceSettings::coarse_step_mm>("coarse_step_mm", "mm", 0.1, 100.0, "sample spacing of the coarse pass"),
    NumField<&PlaceSettings::finalists>("finalists", "", 1, 1000, "layouts that get the full check"),
};

// Most layouts one search may try.
inline constexpr std::size_t kMaxPlaceLayouts = 20000;

// Throws InputError "place: the ranges give more than kMaxPlaceLayouts layouts; ..." (`where` names the section) for
// ranges whose grid is too large to search.
void CheckPlaceLayouts(const PlaceSettings& place, const std::string& where);

}  // namespace waam::analysis

namespace waam::analysis::internal {
// Reads the optional `place:` mapping: each range as [min, max, step] (or one number: that value only). Throws
// InputError naming file:line and key for a range with min > max, a negative step, or a grid over kMaxPlaceLayouts.
void ParsePlaceSection(YamlMap& top, PlaceSettings* out);
}  // namespace waam::analysis::internal
