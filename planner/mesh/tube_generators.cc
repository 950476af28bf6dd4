// Bent tube sweep: straight foot, arc, straight end; section blended from base to top; inner and outer wall surfaces
// with annular end caps, so the mesh is closed and can be sliced like any other part.
#include "planner/mesh/tube_generators.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"
#include "models/core/numbers.h"

namespace waam::planner {
namespace {

// The axis frame at arc length s: point a, tangent t, e1 towards the bend centre (in the x-z plane), e2 = +y.
struct AxisFrame {
  Eigen::Vector3d a, t, e1, e2;
};

AxisFrame FrameAt(const BentTubeSpec& spec, double s) {
  const double L1 = spec.straight_start_mm;
  const double R = spec.bend_radius_mm;
  const double arc = R * spec.bend_angle_rad;
  AxisFrame f;
  f.e2 = Eigen::Vector3d::UnitY();
  const double theta = std::clamp((s - L1) / R, 0.0, spec.bend_angle_rad);
  f.t = Eigen::Vector3d(std::sin(theta), 0.0, std::cos(theta));
  f.e1 = Eigen::Vector3d(std::cos(theta), 0.0, -std::sin(theta));
  const Eigen::Vector3d bend_point(R - R * std::cos(theta), 0.0, L1 + R * std::sin(theta));
  if (s <= L1) {
    f.a = Eigen::Vector3d(0.0, 0.0, s);
  } else if (s <= L1 + arc) {
    f.a = bend_point;
  } else {
    f.a = bend_point + (s - L1 - arc) * f.t;
  }
  return f;
}

// Arc-length stations: every straight and the arc split into pieces no longer than the step.
std::vector<double> Stations(const BentTubeSpec& spec) {
  std::vector<double> s{0.0};
  const double pieces[3] = {spec.straight_start_mm, spec.bend_radius_mm * spec.bend_angle_rad, spec.straight_end_mm};
  double at = 0.0;
  for (double length : pieces) {
    if (length <= 0.0) continue;
    const int n = std::max(1, static_cast<int>(std::ceil(length / spec.axis_step_mm - 1e-9)));
    for (int k = 1; k <= n; ++k) s.push_back(at + length * k / n);
    at += length;
  }
  return s;
}

}  // namespace

double SectionRadius(int sides, double size_mm, double squareness, double phi) {
  const double a = 0.5 * size_mm;
  if (sides == 0) return a;
  if (sides == 4) {
    // Rounded square: the superellipse |x|^p + |y|^p = a^p.
    const double c = std::pow(std::abs(std::cos(phi)), squareness) + std::pow(std::abs(std::sin(phi)), squareness);
    return a / std::pow(c, 1.0 / squareness);
  }
  // Regular n-gon with apothem a, a flat facing phi = 0.
  const double sector = 2.0 * kPi / sides;
  return a / std::cos(std::remainder(phi, sector));
}

BentTubeSpec BentTubeSpecFromParams(const GeneratorParams& p) {
  BentTubeSpec spec;
  spec.diameter_start_mm = p.at("diameter_mm").at(0);
  spec.diameter_end_mm = p.at("diameter_mm").at(1);
  spec.sides_start = static_cast<int>(std::lround(p.at("sides").at(0)));
  spec.sides_end = static_cast<int>(std::lround(p.at("sides").at(1)));
  spec.squareness = p.at("squareness_exponent").at(0);
  spec.wall_mm = p.at("wall_mm").at(0);
  spec.bend_radius_mm = p.at("bend_radius_mm").at(0);
  spec.bend_angle_rad = p.at("bend_angle_deg").at(0) * kPi / 180.0;
  spec.straight_start_mm = p.at("straight_mm").at(0);
  spec.straight_end_mm = p.at("straight_mm").at(1);
  spec.section_points = static_cast<int>(std::lround(p.at("section_points").at(0)));
  spec.axis_step_mm = p.at("axis_step_mm").at(0);
  return spec;
}

TubePart BuildBentTube(const BentTubeSpec& spec, const std::string& where) {
  for (int sides : {spec.sides_start, spec.sides_end}) {
    WAAM_THROW_UNLESS(sides == 0 || sides >= 3,
                      where << ": bent_tube.sides = " << sides << ": must be 0 (circle), 4 (rounded square) or >= 3");
  }
  const int m = spec.section_points;
  const std::vector<double> stations = Stations(spec);
  const double length = stations.back();
  auto radius = [&](double s, double phi) {
    const double f = length > 0.0 ? s / length : 0.0;
    return (1.0 - f) * SectionRadius(spec.sides_start, spec.diameter_start_mm, spec.squareness, phi) +
           f * SectionRadius(spec.sides_end, spec.diameter_end_mm, spec.squareness, phi);
  };

  // Checks that the wall fits inside the section and the inner wall of the bend does not fold.
  TubePart tube;
  double r_min = 1e300;
  for (double s : stations) {
    for (int j = 0; j < m; ++j) r_min = std::min(r_min, radius(s, 2.0 * kPi * j / m));
    const bool in_bend = s >= spec.straight_start_mm - 1e-9 &&
                         s <= spec.straight_start_mm + spec.bend_radius_mm * spec.bend_angle_rad + 1e-9;
    if (in_bend) tube.extent_in_bend_plane_mm = std::max(tube.extent_in_bend_plane_mm, radius(s, 0.0) + radius(s, kPi));
    WAAM_THROW_UNLESS(!in_bend || radius(s, 0.0) + 0.5 * spec.wall_mm < spec.bend_radius_mm,
                      where << ": bent_tube.bend_radius_mm = " << spec.bend_radius_mm
                            << ": the inner wall (" << radius(s, 0.0) + 0.5 * spec.wall_mm
                            << " mm from the axis) would cross the bend centre");
  }
  WAAM_THROW_UNLESS(spec.wall_mm < r_min, where << ": bent_tube.wall_mm = " << spec.wall_mm
                                                << ": must be smaller than the smallest section radius " << r_min
                                                << " mm");

  // Vertices: per station, m outer then m inner points.
  TriangleMesh& mesh = tube.mesh;
  for (double s : stations) {
    const AxisFrame f = FrameAt(spec, s);
    tube.axis_P.push_back(f.a);
    for (int side = 0; side < 2; ++side) {
      for (int j = 0; j < m; ++j) {
        const double phi = 2.0 * kPi * j / m;
        const double r = radius(s, phi) + (side == 0 ? 0.5 : -0.5) * spec.wall_mm;
        mesh.vertices.push_back(f.a + r * (std::cos(phi) * f.e1 + std::sin(phi) * f.e2));
      }
    }
  }
  auto outer = [&](int k, int j) { return k * 2 * m + (j % m); };
  auto inner = [&](int k, int j) { return k * 2 * m + m + (j % m); };
  const int last = static_cast<int>(stations.size()) - 1;
  for (int k = 0; k < last; ++k) {
    for (int j = 0; j < m; ++j) {
      // (e1, e2, t) is right-handed, so these windings face away from the wall material.
      mesh.facets.push_back({outer(k, j), outer(k, j + 1), outer(k + 1, j + 1)});
      mesh.facets.push_back({outer(k, j), outer(k + 1, j + 1), outer(k + 1, j)});
      mesh.facets.push_back({inner(k, j), inner(k + 1, j + 1), inner(k, j + 1)});
      mesh.facets.push_back({inner(k, j), inner(k + 1, j), inner(k + 1, j + 1)});
    }
  }
  for (int j = 0; j < m; ++j) {
    mesh.facets.push_back({outer(0, j), inner(0, j), inner(0, j + 1)});
    mesh.facets.push_back({outer(0, j), inner(0, j + 1), outer(0, j + 1)});
    mesh.facets.push_back({outer(last, j), inner(last, j + 1), inner(last, j)});
    mesh.facets.push_back({outer(last, j), outer(last, j + 1), inner(last, j + 1)});
  }
  return tube;
}

}  // namespace waam::planner
