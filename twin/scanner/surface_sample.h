// Points sampled evenly on a triangle mesh's surface (STL scans, the target surface of the compensation loop).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "planner/mesh/triangle_mesh.h"

namespace waam::twin {

// Points on the surface of `mesh` (mm) about `spacing_mm` (> 0) apart: the vertices of a regular split of every
// facet (deterministic). Used for STL scans and for sampling the target. Throws InputError for spacing_mm <= 0.
std::vector<Eigen::Vector3d> SampleSurface(const planner::TriangleMesh& mesh, double spacing_mm);

// SampleSurface's points with the surface area each stands for, so that statistics over them are per unit area
// whatever the facets' sizes and shapes (a long sliver gets many points, each standing for little area).
struct SurfaceSamples {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> area_mm2;       // one per point; they sum to the area of the facets sampled
  std::size_t skipped_facets = 0;     // facets left out by `skip_bottom`
  double skipped_area_mm2 = 0.0;
};

// The points of SampleSurface(mesh, spacing_mm) with their areas. With `skip_bottom`, the facets facing down
// (normal z < -0.999) that lie in the mesh's lowest plane (every vertex within 1e-6 of the bounding box's size of
// the lowest z) are left out: the face a part stands on while it is scanned on its plate. Throws InputError for
// spacing_mm <= 0. Facets of zero area get no points.
SurfaceSamples SampleSurfaceByArea(const planner::TriangleMesh& mesh, double spacing_mm, bool skip_bottom);

}  // namespace waam::twin
