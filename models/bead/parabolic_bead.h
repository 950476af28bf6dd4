// Parabolic bead cross-section and the wire-feed volume balance (dissertation eq. 3.1-3.4).
#pragma once

namespace waam::models {

// A bead cross-section z(y) = h - 4h/w^2 y^2 for |y| <= w/2, zero outside.
struct ParabolicBead {
  double width_mm = 0.0;
  double height_mm = 0.0;

  // Cross-section area [mm^2] = 2 w h / 3.
  double Area() const;
  // Height [mm] of the bead surface at lateral offset `y_mm` from the bead axis (0 beyond the toes).
  double ProfileZ(double y_mm) const;
  // Throws InputError unless width and height are finite and > 0.
  void Validate() const;
};

// Cross-section area of the wire [mm^2] = pi d^2 / 4; `wire_diameter_mm` > 0.
double WireArea(double wire_diameter_mm);

// Volume balance (eq. 3.4 rearranged): bead area [mm^2] = efficiency * wire area * wire feed / travel speed.
// Speeds in mm/min (> 0), efficiency in (0, 1]. Throws InputError otherwise.
double BeadAreaFromWireFeed(double wire_diameter_mm, double wire_feed_mm_per_min, double travel_speed_mm_per_min,
                            double efficiency = 1.0);

// The travel speed [mm/min] that lays a bead of `area_mm2` at the given wire feed (inverse of BeadAreaFromWireFeed).
double TravelSpeedForArea(double area_mm2, double wire_diameter_mm, double wire_feed_mm_per_min,
                          double efficiency = 1.0);

// Bead width [mm] from height and process (eq. 3.4: w = 3 pi v_w d_w^2 / (8 h v_t), times the efficiency).
double WidthFromVolumeBalance(double height_mm, double wire_diameter_mm, double wire_feed_mm_per_min,
                              double travel_speed_mm_per_min, double efficiency = 1.0);

// The deposition efficiency a measured bead implies: bead area * travel speed / (wire area * wire feed).
double ImpliedEfficiency(const ParabolicBead& bead, double wire_diameter_mm, double wire_feed_mm_per_min,
                         double travel_speed_mm_per_min);

}  // namespace waam::models
