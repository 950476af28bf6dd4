// The one definition of pi for every module (std::numbers::pi), and the degrees-per-radian factor.
#pragma once

#include <numbers>

namespace waam {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = 180.0 / kPi;  // degrees per radian: angle_rad * kDeg is in degrees

}  // namespace waam
