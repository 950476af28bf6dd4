// Even sampling of a mesh surface: the centres of a regular split of every facet.
#include "twin/scanner/surface_sample.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"

namespace waam::twin {

std::vector<Eigen::Vector3d> SampleSurface(const planner::TriangleMesh& mesh, double spacing_mm) {
  WAAM_THROW_UNLESS(spacing_mm > 0.0, "surface sampling spacing " << spacing_mm << " mm: must be > 0");
  std::vector<Eigen::Vector3d> points;
  for (const auto& f : mesh.facets) {
    const Eigen::Vector3d& a = mesh.vertices[f[0]];
    const Eigen::Vector3d& b = mesh.vertices[f[1]];
    const Eigen::Vector3d& c = mesh.vertices[f[2]];
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int n = std::max(1, static_cast<int>(std::ceil(longest / spacing_mm)));
    // Centres of the n^2 sub-triangles of a regular split: each stands for an equal share of the facet area.
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        points.push_back(a + (b - a) * ((i + 1.0 / 3.0) / n) + (c - a) * ((j + 1.0 / 3.0) / n));
        if (i + j + 1 < n) points.push_back(a + (b - a) * ((i + 2.0 / 3.0) / n) + (c - a) * ((j + 2.0 / 3.0) / n));
      }
    }
  }
  return points;
}

}  // namespace waam::twin
