// The ranges `waam place` searches (optional scenario section `place`): where the part stands on the plate, the
// table's home rotation, the positioner's yaw and the arm's base position, and how hard to look.
#pragma once

#include <optional>
#include <string>

namespace waam::planner::internal {
class YamlMap;
}  // namespace waam::planner::internal

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
// Most layouts one search may try.
inline constexpr std::size_t kMaxPlaceLayouts = 20000;

}  // namespace waam::analysis

namespace waam::analysis::internal {
using planner::internal::YamlMap;
// Reads the optional `place:` mapping: each range as [min, max, step] (or one number: that value only). Throws
// InputError naming file:line and key for a range with min > max, a negative step, or a grid over kMaxPlaceLayouts.
void ParsePlaceSection(YamlMap& top, PlaceSettings* out);
}  // namespace waam::analysis::internal
