// The path patterns and overlap models by name (scenario keys path.pattern and path.overlap_model), one table each
// (models/core/enum_names.h).
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

}  // namespace waam::planner
