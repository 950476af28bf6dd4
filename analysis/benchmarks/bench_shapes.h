// Shapes the benchmarks share: the 200 x 150 mm plate with three holes of tests/planner/test_shapes.h.
#pragma once

#include <cmath>
#include <numbers>

#include "planner/geometry/polygon.h"

namespace waam::bench {

// Axis-aligned rectangle (mm), counter-clockwise.
inline planner::Ring Rect(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// A 200 x 150 mm plate with a square hole, a 22 mm round bore (a `bore_sides`-gon) and a tilted slot.
inline planner::PolygonWithHoles HoledPlate(int bore_sides) {
  planner::PolygonWithHoles plate{Rect(0, 0, 200, 150), {}};
  plate.holes.push_back(Rect(30, 30, 70, 70));
  planner::Ring bore;
  for (int k = 0; k < bore_sides; ++k) {
    const double a = 2.0 * std::numbers::pi * k / bore_sides;
    bore.emplace_back(140 + 22 * std::cos(a), 90 + 22 * std::sin(a));
  }
  plate.holes.push_back(bore);
  plate.holes.push_back({{40, 105}, {95, 115}, {92, 130}, {37, 120}});
  return plate;
}

}  // namespace waam::bench
