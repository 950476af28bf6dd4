// Internal: small vector helpers on rings shared by the decomposition and the convex measures.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "planner/geometry/polygon.h"

namespace waam::planner::internal {

// z component of the 2D cross product a x b.
inline double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Vertex i of a closed ring, any integer i (wraps around).
inline const Eigen::Vector2d& At(const Ring& c, int i) {
  const int n = static_cast<int>(c.size());
  return c[((i % n) + n) % n];
}

// Turn at vertex i in radians: > 0 a left (convex, for CCW) turn, < 0 a right turn (a notch).
inline double Turn(const Ring& c, int i) {
  const Eigen::Vector2d e1 = At(c, i) - At(c, i - 1);
  const Eigen::Vector2d e2 = At(c, i + 1) - At(c, i);
  return std::atan2(Cross(e1, e2), e1.dot(e2));
}

// Diagonal of the outline's bounding box in mm (0 for an empty outline).
inline double BoundingDiagonal(const PolygonWithHoles& region) {
  Eigen::AlignedBox2d box;
  for (const Eigen::Vector2d& p : region.outer) box.extend(p);
  return box.isEmpty() ? 0.0 : box.diagonal().norm();
}

}  // namespace waam::planner::internal
