// Lofted elliptic blades along the normals of a cone (the thruster of Dai et al. 2020, Fig. 21, as a procedural part).
#include "planner/mesh/blade_generators.h"

#include <cmath>
#include <limits>

#include "models/core/numbers.h"
#include "planner/mesh/extrude.h"
#include "planner/mesh/mesh_ops.h"

namespace waam::planner {
namespace {

}  // namespace

TriangleMesh BuildConeBlades(const ConeBladeParams& p) {
  const double k = std::isfinite(p.H_mm) ? p.R_mm / p.H_mm : 0.0;  // r(z) = R - k z
  const double r0 = p.R_mm - k * p.root_z_mm;
  std::vector<Eigen::Vector3d> corners;
  auto facet = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    corners.push_back(a);
    corners.push_back(b);
    corners.push_back(c);
  };
  const int m = p.section_points;
  for (int blade = 0; blade < p.blades; ++blade) {
    const double theta = 2.0 * kPi * blade / p.blades;
    const Eigen::Vector3d radial(std::cos(theta), std::sin(theta), 0.0);
    const Eigen::Vector3d normal = (radial + k * Eigen::Vector3d::UnitZ()).normalized();
    const Eigen::Vector3d along = (Eigen::Vector3d::UnitZ() - k * radial).normalized();  // up the generatrix
    const Eigen::Vector3d round(-std::sin(theta), std::cos(theta), 0.0);
    const Eigen::Vector3d root = r0 * radial + p.root_z_mm * Eigen::Vector3d::UnitZ();
    std::vector<std::vector<Eigen::Vector3d>> rings;
    std::vector<Eigen::Vector3d> centres;
    for (int j = 0; j < p.sections; ++j) {
      const double f = static_cast<double>(j) / (p.sections - 1);
      const double s = -p.root_mm + f * (p.span_mm + p.root_mm);
      const double g = std::clamp(s / p.span_mm, 0.0, 1.0);
      const double thickness = p.root_thickness_mm + g * (p.tip_thickness_mm - p.root_thickness_mm);
      const double pitch = (p.pitch_root_deg + g * (p.pitch_tip_deg - p.pitch_root_deg)) * kPi / 180.0;
      const Eigen::Vector3d centre = root + s * normal;
      std::vector<Eigen::Vector3d> ring;
      for (int i = 0; i < m; ++i) {
        const double phi = 2.0 * kPi * i / m;
        const double u = 0.5 * p.chord_mm * std::cos(phi);
        const double v = 0.5 * thickness * std::sin(phi);
        ring.push_back(centre + (u * std::cos(pitch) - v * std::sin(pitch)) * along +
                       (u * std::sin(pitch) + v * std::cos(pitch)) * round);
      }
      rings.push_back(std::move(ring));
      centres.push_back(centre);
    }
    for (int j = 0; j + 1 < p.sections; ++j) {
      for (int i = 0; i < m; ++i) {
        const int n = (i + 1) % m;
        facet(rings[j][i], rings[j + 1][i], rings[j + 1][n]);
        facet(rings[j][i], rings[j + 1][n], rings[j][n]);
      }
    }
    for (int i = 0; i < m; ++i) {
      const int n = (i + 1) % m;
      facet(centres.front(), rings.front()[i], rings.front()[n]);
      facet(centres.back(), rings.back()[n], rings.back()[i]);
    }
  }
  TriangleMesh mesh = WeldTriangles(corners, 1e-9, nullptr);
  // The winding above depends on the handedness of (along, round, normal); make the normals point outward.
  if (EnclosedVolume(mesh) < 0.0) {
    for (auto& f : mesh.facets) std::swap(f[1], f[2]);
  }
  return mesh;
}

TriangleMesh BuildPropeller(ConeBladeParams p, double hub_height_mm) {
  p.H_mm = std::numeric_limits<double>::infinity();
  p.root_mm = 0.0;
  p.root_z_mm = 0.5 * hub_height_mm;
  TriangleMesh mesh = BuildConeBlades(p);
  const double half = p.R_mm - 0.01;
  AppendMesh(ExtrudeRegions({PolygonWithHoles{RectangleRing(-half, -half, half, half), {}}}, 0.0, hub_height_mm),
             &mesh);
  return mesh;
}

}  // namespace waam::planner
