// The feasible travel-speed window of a process and the result of choosing a speed inside it.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace waam::models {

// Travel speeds the process can run [mm/min]: below the window the wall goes wavy, above it humps (003 sec. 6.3.2).
struct SpeedRange {
  double min_mm_per_min = 0.0;
  double max_mm_per_min = 0.0;
  // Throws InputError "<where>: speed range [a, b] mm/min: must satisfy 0 < min <= max" if it is not a window.
  void Validate(const std::string& where) const;
};

nlohmann::json ToJson(const SpeedRange& range);
SpeedRange SpeedRangeFromJson(const nlohmann::json& j, const std::string& where);

// Whether an inverse model had to clamp the speed it computed to the feasible window.
enum class SpeedClamp { kNone, kAtMinimum, kAtMaximum };
std::string ToString(SpeedClamp clamp);

// A travel speed chosen to reach a wanted bead dimension, and what the model says it gives.
struct SpeedChoice {
  double speed_mm_per_min = 0.0;   // commanded speed, inside the feasible window
  double unclamped_mm_per_min = 0.0;  // the exact inverse (may be outside the window or +inf)
  double achieved_mm = 0.0;        // the width (CSW) or height (speed-height) the model predicts at `speed`
  SpeedClamp clamp = SpeedClamp::kNone;
};

// The feasible window for a fit: `*feasible` if given, else the span of the measured `speeds_mm_per_min`.
// Throws InputError naming `where` if the result is not a window.
SpeedRange FitSpeedRange(const std::vector<double>& speeds_mm_per_min, const SpeedRange* feasible,
                         const std::string& where);

// Clamps `wanted` [mm/min] into `range`, recording the side.
SpeedChoice ClampSpeed(double wanted, const SpeedRange& range);

}  // namespace waam::models
