// Feasible speed windows and clamping.
#include "models/bead/speed_range.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"
#include "models/fit/model_file.h"

namespace waam::models {

void SpeedRange::Validate(const std::string& where) const {
  WAAM_THROW_UNLESS(std::isfinite(min_mm_per_min) && std::isfinite(max_mm_per_min) && min_mm_per_min > 0.0 &&
                        min_mm_per_min <= max_mm_per_min,
                    where << ": speed range [" << min_mm_per_min << ", " << max_mm_per_min
                          << "] mm/min: must satisfy 0 < min <= max");
}

nlohmann::json ToJson(const SpeedRange& r) { return {{"min", r.min_mm_per_min}, {"max", r.max_mm_per_min}}; }

SpeedRange SpeedRangeFromJson(const nlohmann::json& j, const std::string& where) {
  SpeedRange r{JsonNumber(j, "/min", where + " feasible_speed_mm_per_min"),
               JsonNumber(j, "/max", where + " feasible_speed_mm_per_min")};
  r.Validate(where);
  return r;
}

std::string ToString(SpeedClamp clamp) {
  switch (clamp) {
    case SpeedClamp::kNone:
      return "none";
    case SpeedClamp::kAtMinimum:
      return "at_minimum";
    case SpeedClamp::kAtMaximum:
      return "at_maximum";
  }
  return "unknown";
}

SpeedChoice ClampSpeed(double wanted, const SpeedRange& range) {
  SpeedChoice c;
  c.unclamped_mm_per_min = wanted;
  c.speed_mm_per_min = wanted;
  // A speed on a bound up to rounding (an inverse of a forward value at the bound) is not a clamp.
  const double slack = 1e-9 * range.max_mm_per_min;
  if (std::abs(wanted - range.min_mm_per_min) <= slack) {
    c.speed_mm_per_min = range.min_mm_per_min;
  } else if (std::abs(wanted - range.max_mm_per_min) <= slack) {
    c.speed_mm_per_min = range.max_mm_per_min;
  } else if (!(wanted >= range.min_mm_per_min)) {  // also catches NaN
    c.speed_mm_per_min = range.min_mm_per_min;
    c.clamp = SpeedClamp::kAtMinimum;
  } else if (wanted > range.max_mm_per_min) {
    c.speed_mm_per_min = range.max_mm_per_min;
    c.clamp = SpeedClamp::kAtMaximum;
  }
  return c;
}

SpeedRange FitSpeedRange(const std::vector<double>& speeds_mm_per_min, const SpeedRange* feasible,
                         const std::string& where) {
  SpeedRange range;
  if (feasible != nullptr) {
    range = *feasible;
  } else if (!speeds_mm_per_min.empty()) {
    const auto [lo, hi] = std::minmax_element(speeds_mm_per_min.begin(), speeds_mm_per_min.end());
    range = {*lo, *hi};
  }
  range.Validate(where);
  return range;
}

}  // namespace waam::models
