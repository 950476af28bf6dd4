// The path patterns, overlap models and island orders by name (scenario keys path.pattern, path.overlap_model,
// path.island_order), one table each (models/core/enum_names.h).
#pragma once

#include <array>

#include "models/core/enum_names.h"

namespace waam::planner {

// path.pattern
enum class Pattern { kContour, kZigzag, kHybrid, kContinuous, kEulerian, kSpiral };
constexpr std::array<EnumName<Pattern>, 6> EnumNames(Pattern) {
  return {{{Pattern::kContour, "contour"}, {Pattern::kZigzag, "zigzag"}, {Pattern::kHybrid, "hybrid"},
           {Pattern::kContinuous, "continuous"}, {Pattern::kEulerian, "eulerian"}, {Pattern::kSpiral, "spiral"}}};
}
WAAM_ENUM_JSON(Pattern)
// path.overlap_model
enum class OverlapModel { kProposed, kExisting };
constexpr std::array<EnumName<OverlapModel>, 2> EnumNames(OverlapModel) {
  return {{{OverlapModel::kProposed, "proposed"}, {OverlapModel::kExisting, "existing"}}};
}
WAAM_ENUM_JSON(OverlapModel)
// path.island_order: the order of a layer's islands (or passes) (planner/timeline/island_order.h)
enum class IslandOrder { kAsPlanned, kRoundRobin, kCoolestFirst };
constexpr std::array<EnumName<IslandOrder>, 3> EnumNames(IslandOrder) {
  return {{{IslandOrder::kAsPlanned, "as_planned"}, {IslandOrder::kRoundRobin, "round_robin"},
           {IslandOrder::kCoolestFirst, "coolest_first"}}};
}
WAAM_ENUM_JSON(IslandOrder)

}  // namespace waam::planner
