// Test polygons for the path planner: L, T, U, a plate with holes, random stars and four Ding-like geometries.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "planner/geometry/polygon.h"

namespace waam::planner::testing {

inline Ring Poly(std::initializer_list<std::pair<double, double>> xy) {
  Ring r;
  for (const auto& [x, y] : xy) r.emplace_back(x, y);
  return r;
}

// Axis-aligned rectangle, CCW (or CW for a hole).
inline Ring Rect(double x0, double y0, double x1, double y1, bool hole = false) {
  Ring r = Poly({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
  if (hole) std::reverse(r.begin(), r.end());
  return r;
}

// Regular n-gon of radius r around (cx, cy); CW when `hole`.
inline Ring Circle(double cx, double cy, double r, int n, bool hole = false) {
  Ring ring;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    ring.emplace_back(cx + r * std::cos(a), cy + r * std::sin(a));
  }
  if (hole) std::reverse(ring.begin(), ring.end());
  return ring;
}

inline PolygonWithHoles LShape() { return {Poly({{0, 0}, {100, 0}, {100, 40}, {40, 40}, {40, 100}, {0, 100}}), {}}; }

inline PolygonWithHoles TShape() {
  return {Poly({{40, 0}, {80, 0}, {80, 60}, {120, 60}, {120, 100}, {0, 100}, {0, 60}, {40, 60}}), {}};
}

inline PolygonWithHoles UShape() {
  return {Poly({{0, 0}, {100, 0}, {100, 100}, {70, 100}, {70, 30}, {30, 30}, {30, 100}, {0, 100}}), {}};
}

// ~200 x 150 mm plate with a square hole, a round hole and a tilted slot.
inline PolygonWithHoles PlateWithHoles() {
  PolygonWithHoles p{Rect(0, 0, 200, 150), {}};
  p.holes.push_back(Rect(30, 30, 70, 70, true));
  p.holes.push_back(Circle(140, 90, 22, 24, true));
  Ring slot = Poly({{40, 105}, {95, 115}, {92, 130}, {37, 120}});
  std::reverse(slot.begin(), slot.end());
  p.holes.push_back(slot);
  return p;
}

// Star-shaped (so simple) polygon around the origin: vertex k at angle 2 pi (k + U(0, 0.8)) / n and radius
// U(0.35, 1) * radius.
inline PolygonWithHoles RandomStar(std::mt19937_64& rng, int n, double radius) {
  std::uniform_real_distribution<double> jitter(0.0, 0.8), scale(0.35, 1.0);
  Ring ring;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * (k + jitter(rng)) / n;
    const double r = radius * scale(rng);
    ring.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return {ring, {}};
}

// Four geometries shaped like the test parts of Ding et al. 2014 Table 2 (not their exact drawings, which the
// paper gives only as pictures): 1 an irregular polygon with notches and an island (their Fig. 3b / 5),
// 2 a thin-walled comb, 3 a thin-walled frame with ribs and cells, 4 a solid block with slots and a bore.
inline std::vector<std::pair<std::string, PolygonWithHoles>> DingLikeShapes() {
  std::vector<std::pair<std::string, PolygonWithHoles>> shapes;
  PolygonWithHoles island{Poly({{0, 0}, {60, 10}, {110, 0}, {120, 50}, {90, 60}, {110, 100}, {50, 110}, {0, 90},
                                {20, 50}}),
                          {}};
  Ring hole = Poly({{45, 35}, {75, 40}, {70, 70}, {50, 65}});
  std::reverse(hole.begin(), hole.end());
  island.holes.push_back(hole);
  shapes.emplace_back("1 polygon with island", island);
  shapes.emplace_back("2 thin-walled comb",
                      PolygonWithHoles{Poly({{0, 0}, {130, 0}, {130, 12}, {122, 12}, {122, 80}, {110, 80}, {110, 12},
                                             {71, 12}, {71, 80}, {59, 80}, {59, 12}, {20, 12}, {20, 80}, {8, 80},
                                             {8, 12}, {0, 12}}),
                                       {}});
  PolygonWithHoles frame{Rect(0, 0, 140, 100), {}};
  for (double x0 : {10.0, 75.0}) {
    for (double y0 : {10.0, 55.0}) frame.holes.push_back(Rect(x0, y0, x0 + 55, y0 + 35, true));
  }
  shapes.emplace_back("3 thin-walled frame", frame);
  PolygonWithHoles block{Poly({{0, 0}, {120, 0}, {120, 35}, {95, 35}, {95, 65}, {120, 65}, {120, 100}, {0, 100},
                               {0, 65}, {25, 65}, {25, 35}, {0, 35}}),
                         {}};
  block.holes.push_back(Circle(60, 50, 12, 24, true));
  shapes.emplace_back("4 solid block", block);
  return shapes;
}

}  // namespace waam::planner::testing
