// Even sampling of a mesh surface: the centres of a regular split of every facet, each with the area it stands for.
#include "twin/scanner/surface_sample.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/error.h"

namespace waam::twin {
namespace {

// Appends the centres of the n^2 sub-triangles of a regular split of (a, b, c), n from the longest edge; each
// stands for an equal share of the facet's area. Returns how many were appended.
std::size_t SplitCentres(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                         double spacing_mm, std::vector<Eigen::Vector3d>* points) {
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  const int n = std::max(1, static_cast<int>(std::ceil(longest / spacing_mm)));
  for (int i = 0; i < n; ++i) {
    for (int j = 0; i + j < n; ++j) {
      points->push_back(a + (b - a) * ((i + 1.0 / 3.0) / n) + (c - a) * ((j + 1.0 / 3.0) / n));
      if (i + j + 1 < n) points->push_back(a + (b - a) * ((i + 2.0 / 3.0) / n) + (c - a) * ((j + 2.0 / 3.0) / n));
    }
  }
  return static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
}

}  // namespace

std::vector<Eigen::Vector3d> SampleSurface(const planner::TriangleMesh& mesh, double spacing_mm) {
  WAAM_THROW_UNLESS(spacing_mm > 0.0, "surface sampling spacing " << spacing_mm << " mm: must be > 0");
  std::vector<Eigen::Vector3d> points;
  for (const auto& f : mesh.facets) {
    SplitCentres(mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]], spacing_mm, &points);
  }
  return points;
}

SurfaceSamples SampleSurfaceByArea(const planner::TriangleMesh& mesh, double spacing_mm, bool skip_bottom) {
  WAAM_THROW_UNLESS(spacing_mm > 0.0, "surface sampling spacing " << spacing_mm << " mm: must be > 0");
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Eigen::Vector3d& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const double tol = mesh.vertices.empty() ? 0.0 : 1e-6 * std::max(1.0, (hi - lo).norm());
  SurfaceSamples s;
  for (const auto& f : mesh.facets) {
    const Eigen::Vector3d& a = mesh.vertices[f[0]];
    const Eigen::Vector3d& b = mesh.vertices[f[1]];
    const Eigen::Vector3d& c = mesh.vertices[f[2]];
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double area = 0.5 * cross.norm();
    if (!(area > 0.0)) continue;  // a degenerate facet has no surface to stand for
    const bool on_bottom = std::max({a.z(), b.z(), c.z()}) <= lo.z() + tol;
    if (skip_bottom && on_bottom && cross.z() < -0.999 * cross.norm()) {
      ++s.skipped_facets;
      s.skipped_area_mm2 += area;
      continue;
    }
    const std::size_t n = SplitCentres(a, b, c, spacing_mm, &s.points);
    s.area_mm2.resize(s.points.size(), area / static_cast<double>(n));
  }
  return s;
}

}  // namespace waam::twin
