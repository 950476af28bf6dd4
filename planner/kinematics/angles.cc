// Joint-angle helpers shared by the arm and positioner kinematics.
#include "planner/kinematics/angles.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace waam::planner {

double NearestAngleCopy(double q, double lo, double hi, double target) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  // remainder() returns q itself for |q| <= pi (the quotient rounds to 0): skip the slow call there.
  if (!(std::abs(q) <= std::numbers::pi)) q = std::remainder(q, kTwoPi);
  double best = q;
  double best_cost = std::numeric_limits<double>::infinity();
  for (int k = -2; k <= 2; ++k) {
    const double c = q + k * kTwoPi;
    const bool inside = c >= lo && c <= hi;
    const double cost = (inside ? 0.0 : 1e6) + std::abs(c - target);
    if (cost < best_cost) {
      best_cost = cost;
      best = c;
    }
  }
  return best;
}

}  // namespace waam::planner
