// Small hand-built plans for the twin tests: straight beads, parallel-bead blocks, squares, double-bead crosses.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "models/core/numbers.h"
#include "planner/mesh/triangle_mesh.h"
#include "planner/path/tool_path.h"

namespace waam::twin::testing {

inline planner::PathPoint Pt(double x, double y, double z, bool weld, double w, double h, double speed) {
  planner::PathPoint p;
  p.p_P = Eigen::Vector3d(x, y, z);
  p.bead_width_mm = w;
  p.bead_height_mm = h;
  p.speed_mm_s = speed;
  p.weld = weld;
  return p;
}

// Appends a weld pass through `xy` (arc start at the first point) at height z to `layer`.
inline void AddPass(planner::LayerPath* layer, const std::vector<Eigen::Vector2d>& xy, double z, double w, double h,
                    double speed) {
  for (std::size_t i = 0; i < xy.size(); ++i) {
    layer->points.push_back(Pt(xy[i].x(), xy[i].y(), z, i > 0, w, h, speed));
  }
}

// A block of straight beads along y (length `length`), at the x positions `xs`, `layers` layers of height `dz`.
// Beads alternate direction, each its own pass; the layer region is the rectangle the beads cover.
inline planner::Plan ParallelBlock(const std::vector<double>& xs, double length, int layers, double dz, double w,
                                   double h, double speed) {
  planner::Plan plan;
  for (int l = 0; l < layers; ++l) {
    planner::LayerPath layer;
    layer.index = l;
    layer.z_mm = (l + 1) * dz;
    for (std::size_t i = 0; i < xs.size(); ++i) {
      const bool up = (i + static_cast<std::size_t>(l)) % 2 == 0;
      AddPass(&layer, {{xs[i], up ? 0.0 : length}, {xs[i], up ? length : 0.0}}, layer.z_mm, w, h, speed);
    }
    planner::PolygonWithHoles region;
    region.outer = {{xs.front() - w / 2, 0.0}, {xs.back() + w / 2, 0.0}, {xs.back() + w / 2, length},
                    {xs.front() - w / 2, length}};
    layer.slice.push_back(region);
    plan.layers.push_back(layer);
  }
  return plan;
}

// Bead centre positions across a block: outer contour, second contour at d2, zigzag at d1 from it, then l apart,
// mirrored, for `zigzag` interior beads (003 Fig. 20-22).
inline std::vector<double> BlockPositions(double d2, double d1, double l, int zigzag) {
  std::vector<double> xs = {0.0, d2};
  double x = d2 + d1;
  for (int i = 0; i < zigzag; ++i, x += l) xs.push_back(x);
  x = xs.back() + d1;
  xs.push_back(x);
  xs.push_back(x + d2);
  return xs;
}

// A square layer region [0, a]^2 filled by an outer contour loop (w/2 in from the edge) and a raster of lines along x
// spaced `l`, starting `d1` inside the contour. continuous = true: contour and serpentine raster in ONE pass (Ding's
// continuous path); false: the contour is one pass and every raster line its own pass (hybrid, many starts).
inline planner::Plan SquareLayers(double a, int layers, double w, double h, double l, double d1, double speed,
                                  bool continuous) {
  planner::Plan plan;
  const double c = w / 2;
  for (int k = 0; k < layers; ++k) {
    planner::LayerPath layer;
    layer.index = k;
    layer.z_mm = (k + 1) * 0.9 * h;
    const std::vector<Eigen::Vector2d> loop = {{c, c}, {a - c, c}, {a - c, a - c}, {c, a - c}, {c, c}};
    std::vector<std::vector<Eigen::Vector2d>> lines;
    const double x0 = c + d1;
    const double x1 = a - c - d1;
    const int n = static_cast<int>(std::floor((a - 2 * (c + d1)) / l)) + 1;
    const double pitch = n > 1 ? (a - 2 * (c + d1)) / (n - 1) : 0.0;
    for (int i = 0; i < n; ++i) {
      const double y = c + d1 + i * pitch;
      lines.push_back(i % 2 == 0 ? std::vector<Eigen::Vector2d>{{x0, y}, {x1, y}}
                                 : std::vector<Eigen::Vector2d>{{x1, y}, {x0, y}});
    }
    if (continuous) {
      std::vector<Eigen::Vector2d> all = loop;
      for (const auto& line : lines) all.insert(all.end(), line.begin(), line.end());
      AddPass(&layer, all, layer.z_mm, w, h, speed);
    } else {
      AddPass(&layer, loop, layer.z_mm, w, h, speed);
      for (const auto& line : lines) AddPass(&layer, line, layer.z_mm, w, h, speed);
    }
    planner::PolygonWithHoles region;
    region.outer = {{0, 0}, {a, 0}, {a, a}, {0, a}};
    layer.slice.push_back(region);
    plan.layers.push_back(layer);
  }
  return plan;
}

// Outline (CCW) of two straight strips of half-width `a` crossing at the origin at angle `theta` (radians), each arm
// `arm` long from the centre: the X junction of 003 Appendix A1 groups D/F. Reflex corners lie on the bisectors.
inline std::vector<Eigen::Vector2d> CrossOutline(double a, double theta, double arm) {
  const double phi[5] = {0.0, theta, kPi, kPi + theta, 2.0 * kPi};
  std::vector<Eigen::Vector2d> ring;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d d(std::cos(phi[k]), std::sin(phi[k]));
    const Eigen::Vector2d n(-d.y(), d.x());
    ring.push_back(arm * d - a * n);
    ring.push_back(arm * d + a * n);
    const double gap = phi[k + 1] - phi[k];
    const double mid = 0.5 * (phi[k] + phi[k + 1]);
    ring.push_back(a / std::sin(gap / 2.0) * Eigen::Vector2d(std::cos(mid), std::sin(mid)));
  }
  return ring;
}

// A double-bead X junction planned with a plain contour: one closed loop per layer l/2 off the rib centre lines
// (two beads per rib, l apart), `layers` layers; the layer region is the rib outline (half-width (l + w)/2).
inline planner::Plan CrossJunction(double theta, double arm, int layers, double w, double h, double l, double dz,
                                   double speed) {
  planner::Plan plan;
  for (int k = 0; k < layers; ++k) {
    planner::LayerPath layer;
    layer.index = k;
    layer.z_mm = (k + 1) * dz;
    std::vector<Eigen::Vector2d> loop = CrossOutline(l / 2, theta, arm);
    // Start at the tip of the first arm, away from the junction.
    std::rotate(loop.begin(), loop.begin() + 1, loop.end());
    loop.push_back(loop.front());
    AddPass(&layer, loop, layer.z_mm, w, h, speed);
    planner::PolygonWithHoles region;
    region.outer = CrossOutline((l + w) / 2, theta, arm + w / 2);
    layer.slice.push_back(region);
    plan.layers.push_back(layer);
  }
  return plan;
}

// Closed box mesh [lo, hi] with outward (counter-clockwise seen from outside) facets.
inline planner::TriangleMesh BoxMesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  planner::TriangleMesh mesh;
  for (int k = 0; k < 8; ++k) {
    mesh.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    mesh.facets.push_back({q[0], q[1], q[2]});
    mesh.facets.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}

}  // namespace waam::twin::testing
