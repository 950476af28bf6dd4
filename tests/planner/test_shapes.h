// Test polygons for the path planner: L, T, U, a plate with holes, random stars, four Ding-like geometries and
// round parts (ellipses, rounded rectangles, sliced cylinders).
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

// Ellipse with semi-axes a, b (mm) around the origin, its a axis at `angle_rad` from +x, as an n-gon; CCW.
inline Ring Ellipse(double a, double b, double angle_rad, int n) {
  Ring ring;
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * std::numbers::pi * k / n;
    const double x = a * std::cos(t), y = b * std::sin(t);
    ring.emplace_back(c * x - s * y, s * x + c * y);
  }
  return ring;
}

// Rectangle [0, width] x [0, height] (mm) with corners rounded to `radius_mm`, each quarter arc in `arc_segments`
// straight pieces; CCW.
inline Ring RoundedRect(double width, double height, double radius_mm, int arc_segments) {
  Ring ring;
  const double cx[4] = {width - radius_mm, radius_mm, radius_mm, width - radius_mm};
  const double cy[4] = {height - radius_mm, height - radius_mm, radius_mm, radius_mm};
  // Corner q (NE, NW, SW, SE) is the quarter arc from angle q pi/2 to (q + 1) pi/2; SE first keeps the ring CCW.
  for (int q : {3, 0, 1, 2}) {
    for (int k = 0; k <= arc_segments; ++k) {
      const double a = 0.5 * std::numbers::pi * (q + static_cast<double>(k) / arc_segments);
      ring.emplace_back(cx[q] + radius_mm * std::cos(a), cy[q] + radius_mm * std::sin(a));
    }
  }
  return ring;
}

// What a planar slicer returns for a faceted cylinder of `n` sides and radius r (mm): the regular n-gon with one
// more point on every edge (where the cut plane crosses the side facet's diagonal), at a fraction U(0.02, 0.98) of
// the edge and moved U(-jitter, jitter) mm across it (float STL coordinates and Clipper's grid). Seeded, CCW.
inline Ring SlicedCylinder(std::mt19937_64& rng, double r, int n, double jitter_mm) {
  std::uniform_real_distribution<double> along(0.02, 0.98), across(-jitter_mm, jitter_mm);
  const Ring corners = Circle(0.0, 0.0, r, n);
  Ring ring;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d a = corners[k], b = corners[(k + 1) % n];
    const Eigen::Vector2d normal = Eigen::Vector2d((b - a).y(), -(b - a).x()).normalized();
    ring.push_back(a);
    ring.push_back(a + along(rng) * (b - a) + across(rng) * normal);
  }
  return ring;
}

// A curved wall section: the band between radii r0 < r1 over `sweep_deg` (centred on +x), each arc tessellated
// into n chords, CCW: every vertex of the inner arc is a shallow notch.
inline PolygonWithHoles ArcBand(double r0, double r1, double sweep_deg, int n) {
  Ring ring;
  const double half = 0.5 * sweep_deg * std::numbers::pi / 180.0;
  auto at = [&](double r, int k) {
    const double a = -half + 2.0 * half * k / n;
    return Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
  };
  for (int k = 0; k <= n; ++k) ring.push_back(at(r1, k));
  for (int k = n; k >= 0; --k) ring.push_back(at(r0, k));
  return {ring, {}};
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
