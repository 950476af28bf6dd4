// The cup with two handles of the dissertation's decomposition example (003 sec. 5.4, Fig. 52) as a procedural mesh.
#include "planner/mesh/cup_generator.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/mesh/extrude.h"
#include "planner/mesh/mesh_ops.h"

namespace waam::planner {
namespace {

// Welds a triangle soup into one shell and turns its facets outward.
TriangleMesh Shell(const std::vector<Eigen::Vector3d>& corners) {
  TriangleMesh mesh = WeldTriangles(corners, 1e-9, nullptr);
  if (EnclosedVolume(mesh) < 0.0) {
    for (auto& f : mesh.facets) std::swap(f[1], f[2]);
  }
  return mesh;
}

// The cup body: the profile (r, z) revolved round z; points on the axis close the bottom without a hole.
TriangleMesh CupBody(const CupParams& p) {
  const double R = p.radius_mm;
  const std::vector<Eigen::Vector2d> profile = {{0.0, 0.0},
                                                {R, 0.0},
                                                {R, p.height_mm},
                                                {R - p.wall_mm, p.height_mm},
                                                {R - p.wall_mm, p.bottom_mm},
                                                {0.0, p.bottom_mm}};
  std::vector<Eigen::Vector3d> corners;
  auto at = [&](const Eigen::Vector2d& rz, int i) {
    const double phi = 2.0 * kPi * i / p.segments;
    return Eigen::Vector3d(rz.x() * std::cos(phi), rz.x() * std::sin(phi), rz.y());
  };
  for (std::size_t k = 0; k + 1 < profile.size(); ++k) {
    for (int i = 0; i < p.segments; ++i) {
      const Eigen::Vector3d a = at(profile[k], i), b = at(profile[k], i + 1);
      const Eigen::Vector3d c = at(profile[k + 1], i + 1), d = at(profile[k + 1], i);
      for (const auto& tri : {std::array{a, b, c}, std::array{a, c, d}}) {
        if (IsDegenerateFacet(tri[0], tri[1], tri[2])) continue;  // fans at the axis
        corners.insert(corners.end(), tri.begin(), tri.end());
      }
    }
  }
  return Shell(corners);
}

// One handle at angle psi round z: a tube along the half circle c(theta) = (R + r_h cos theta, 0, z_h + r_h sin
// theta), theta in [-90, 90] deg, its end rings pressed radially onto the cylinder r = R + gap.
TriangleMesh Handle(const CupParams& p, double psi) {
  const double R = p.radius_mm, rh = p.handle_radius_mm, a = p.handle_tube_mm;
  const double rc = R + kCupHandleGapMm;
  const int n = p.handle_sections, m = p.handle_points;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  std::vector<std::vector<Eigen::Vector3d>> rings(n + 1);
  for (int j = 0; j <= n; ++j) {
    const double theta = -0.5 * kPi + kPi * j / n;
    const Eigen::Vector3d centre(R + rh * std::cos(theta), 0.0, p.handle_z_mm + rh * std::sin(theta));
    const Eigen::Vector3d radial(std::cos(theta), 0.0, std::sin(theta));
    for (int i = 0; i < m; ++i) {
      const double phi = 2.0 * kPi * i / m;
      Eigen::Vector3d q = centre + a * (std::cos(phi) * radial + std::sin(phi) * Eigen::Vector3d::UnitY());
      if (j == 0 || j == n) q.x() = std::sqrt(rc * rc - q.y() * q.y());
      rings[j].push_back(turn * q);
    }
  }
  const Eigen::Vector3d cap0 = turn * Eigen::Vector3d(rc, 0.0, p.handle_z_mm - rh);
  const Eigen::Vector3d cap1 = turn * Eigen::Vector3d(rc, 0.0, p.handle_z_mm + rh);
  std::vector<Eigen::Vector3d> corners;
  auto facet = [&](const Eigen::Vector3d& x, const Eigen::Vector3d& y, const Eigen::Vector3d& z) {
    corners.insert(corners.end(), {x, y, z});
  };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < m; ++i) {
      const int k = (i + 1) % m;
      facet(rings[j][i], rings[j + 1][i], rings[j + 1][k]);
      facet(rings[j][i], rings[j + 1][k], rings[j][k]);
    }
  }
  for (int i = 0; i < m; ++i) {
    const int k = (i + 1) % m;
    facet(cap0, rings[0][i], rings[0][k]);
    facet(cap1, rings[n][k], rings[n][i]);
  }
  return Shell(corners);
}

}  // namespace

TriangleMesh BuildCupTwoHandles(const CupParams& p, const std::string& where) {
  WAAM_THROW_UNLESS(p.wall_mm < p.radius_mm, where << ": cup_two_handles.wall_mm = " << p.wall_mm
                                                   << ": must be < radius_mm = " << p.radius_mm);
  WAAM_THROW_UNLESS(p.bottom_mm < p.height_mm, where << ": cup_two_handles.bottom_mm = " << p.bottom_mm
                                                     << ": must be < height_mm = " << p.height_mm);
  WAAM_THROW_UNLESS(p.handle_tube_mm < p.handle_radius_mm,
                    where << ": cup_two_handles.handle_mm = [" << p.handle_radius_mm << ", " << p.handle_tube_mm
                          << "]: the tube radius must be < the handle radius");
  WAAM_THROW_UNLESS(p.handle_tube_mm <= 0.5 * p.radius_mm,
                    where << ": cup_two_handles.handle_mm tube radius " << p.handle_tube_mm
                          << " mm: must be <= radius_mm / 2 = " << 0.5 * p.radius_mm);
  const double reach = p.handle_radius_mm + p.handle_tube_mm;
  WAAM_THROW_UNLESS(p.handle_z_mm - reach >= 0.0 && p.handle_z_mm + reach <= p.height_mm,
                    where << ": cup_two_handles.handle_z_mm = " << p.handle_z_mm << ": the handles span "
                          << p.handle_z_mm - reach << " to " << p.handle_z_mm + reach
                          << " mm and must stay within the cup's height [0, " << p.height_mm << "]");
  TriangleMesh mesh = CupBody(p);
  AppendMesh(Handle(p, 0.0), &mesh);
  AppendMesh(Handle(p, kPi), &mesh);
  return mesh;
}

double CupTwoHandlesVolume(const CupParams& p) {
  const double R = p.radius_mm, r = p.radius_mm - p.wall_mm;
  const double cup = kPi * (R * R * p.height_mm - r * r * (p.height_mm - p.bottom_mm));
  const double handle = kPi * kPi * p.handle_tube_mm * p.handle_tube_mm * p.handle_radius_mm;  // Pappus, half torus
  return cup + 2.0 * handle;
}

}  // namespace waam::planner
