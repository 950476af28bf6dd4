// Parabolic bead (dissertation eq. 3.1-3.3) and the wire-feed volume balance (eq. 3.4).
#include "models/bead/parabolic_bead.h"

#include <cmath>
#include <numbers>

#include "models/core/error.h"

namespace waam::models {
namespace {
void CheckPositive(double value, const char* what, const char* unit) {
  WAAM_THROW_UNLESS(std::isfinite(value) && value > 0.0, what << " = " << value << " " << unit << ": must be > 0");
}
void CheckEfficiency(double efficiency) {
  WAAM_THROW_UNLESS(efficiency > 0.0 && efficiency <= 1.0,
                    "deposition efficiency = " << efficiency << ": must be in (0, 1]");
}
}  // namespace

void ParabolicBead::Validate() const {
  CheckPositive(width_mm, "bead width", "mm");
  CheckPositive(height_mm, "bead height", "mm");
}

// Eq. 3.3: A = 2 * integral_0^{w/2} (h - 4h/w^2 y^2) dy = 2wh/3.
double ParabolicBead::Area() const { return 2.0 * width_mm * height_mm / 3.0; }

// Eq. 3.2: z = -4h/w^2 y^2 + h (a = -4h/w^2, b = h in eq. 3.1).
double ParabolicBead::ProfileZ(double y_mm) const {
  const double half = 0.5 * width_mm;
  if (std::abs(y_mm) >= half) return 0.0;
  return height_mm * (1.0 - (y_mm * y_mm) / (half * half));
}

double WireArea(double wire_diameter_mm) {
  CheckPositive(wire_diameter_mm, "wire diameter", "mm");
  return std::numbers::pi * wire_diameter_mm * wire_diameter_mm / 4.0;
}

// Volume per unit time: A * v_t = eta * (pi d^2 / 4) * v_w.
double BeadAreaFromWireFeed(double wire_diameter_mm, double wire_feed_mm_per_min, double travel_speed_mm_per_min,
                            double efficiency) {
  CheckPositive(wire_feed_mm_per_min, "wire feed", "mm/min");
  CheckPositive(travel_speed_mm_per_min, "travel speed", "mm/min");
  CheckEfficiency(efficiency);
  return efficiency * WireArea(wire_diameter_mm) * wire_feed_mm_per_min / travel_speed_mm_per_min;
}

double TravelSpeedForArea(double area_mm2, double wire_diameter_mm, double wire_feed_mm_per_min, double efficiency) {
  CheckPositive(area_mm2, "bead area", "mm^2");
  CheckPositive(wire_feed_mm_per_min, "wire feed", "mm/min");
  CheckEfficiency(efficiency);
  return efficiency * WireArea(wire_diameter_mm) * wire_feed_mm_per_min / area_mm2;
}

// Eq. 3.4: 2wh/3 * v_t = pi d^2/4 * v_w  =>  w = 3 pi v_w d^2 / (8 h v_t).
double WidthFromVolumeBalance(double height_mm, double wire_diameter_mm, double wire_feed_mm_per_min,
                              double travel_speed_mm_per_min, double efficiency) {
  CheckPositive(height_mm, "bead height", "mm");
  return 1.5 * BeadAreaFromWireFeed(wire_diameter_mm, wire_feed_mm_per_min, travel_speed_mm_per_min, efficiency) /
         height_mm;
}

double ImpliedEfficiency(const ParabolicBead& bead, double wire_diameter_mm, double wire_feed_mm_per_min,
                         double travel_speed_mm_per_min) {
  bead.Validate();
  CheckPositive(wire_feed_mm_per_min, "wire feed", "mm/min");
  CheckPositive(travel_speed_mm_per_min, "travel speed", "mm/min");
  return bead.Area() * travel_speed_mm_per_min / (WireArea(wire_diameter_mm) * wire_feed_mm_per_min);
}

}  // namespace waam::models
