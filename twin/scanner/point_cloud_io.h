// Reading scans as point clouds (PLY ascii / binary_little_endian, XYZ text, STL) and writing PLY with deviations.
#pragma once

#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "planner/mesh/triangle_mesh.h"

namespace waam::twin {

// Largest point count accepted from a scan file (a corrupt header must not allocate gigabytes).
inline constexpr std::size_t kMaxScanPoints = 50'000'000;

// Reads the scan `path` (mm, part frame) by its extension: .ply (vertex x, y, z as float or double; other vertex
// properties and other elements are skipped; ascii or binary_little_endian), .xyz/.txt (one "x y z" per line, more
// columns ignored, '#' comments and blank lines skipped) or .stl (the surface sampled every `stl_spacing_mm`, > 0).
// Throws InputError with one line naming the file and the line (or vertex, facet) and the rule broken.
std::vector<Eigen::Vector3d> ReadPointCloud(const std::filesystem::path& path, double stl_spacing_mm = 1.0);

// Points on the surface of `mesh` about `spacing_mm` (> 0) apart: the vertices of a regular split of every facet
// (deterministic). Used for STL scans and for sampling the target.
std::vector<Eigen::Vector3d> SampleSurface(const planner::TriangleMesh& mesh, double spacing_mm);

// Writes points with a per-point scalar `deviation_mm` (same size) as binary_little_endian PLY, atomically.
void WritePlyWithDeviation(const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& points,
                           const std::vector<double>& deviation_mm);

}  // namespace waam::twin
