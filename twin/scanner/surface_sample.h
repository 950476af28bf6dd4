// Points sampled evenly on a triangle mesh's surface (STL scans, the target surface of the compensation loop).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "planner/mesh/triangle_mesh.h"

namespace waam::twin {

// Points on the surface of `mesh` (mm) about `spacing_mm` (> 0) apart: the vertices of a regular split of every
// facet (deterministic). Used for STL scans and for sampling the target. Throws InputError for spacing_mm <= 0.
std::vector<Eigen::Vector3d> SampleSurface(const planner::TriangleMesh& mesh, double spacing_mm);

}  // namespace waam::twin
