// Reading scans as point clouds (PLY ascii / binary_little_endian, XYZ text, STL) and writing PLY with deviations.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace waam::analysis {

// Largest point count accepted from a scan file (a corrupt header must not allocate gigabytes).
inline constexpr std::size_t kMaxScanPoints = 50'000'000;

// Reads the scan `path` (mm, part frame) by its extension: .ply (vertex x, y, z as float or double; other vertex
// properties and other elements are skipped; ascii or binary_little_endian), .xyz/.txt (one "x y z" per line, more
// columns ignored, '#' comments and blank lines skipped) or .stl (the surface sampled every `stl_spacing_mm`, > 0,
// by twin::SampleSurface).
// Throws InputError with one line naming the file and the line (or vertex, facet) and the rule broken.
std::vector<Eigen::Vector3d> ReadPointCloud(const std::filesystem::path& path, double stl_spacing_mm = 1.0);

// A scan's points with what each counts for in its statistics.
struct ScanCloud {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weight;           // 1 per point of a .ply or .xyz; the area (mm^2) a sampled STL point stands for
  bool area_weighted = false;           // true for an STL
  std::size_t bottom_facets_skipped = 0;  // STL facets left out as the face the part stands on
  double bottom_area_skipped_mm2 = 0.0;
};

// ReadPointCloud's points with their weights. An STL's points are weighted by area (twin::SampleSurfaceByArea), and
// with `skip_bottom` the facets the part stands on (facing down in its lowest plane) are left out: a part scanned on
// its plate shows no bottom. Throws InputError as ReadPointCloud, and for an STL that has nothing left to sample.
ScanCloud ReadScan(const std::filesystem::path& path, double stl_spacing_mm, bool skip_bottom);

// Writes points (mm) with a per-point scalar `deviation_mm` (same size) as binary_little_endian PLY, atomically.
// Throws OutputError naming the path when the file cannot be written.
void WritePlyWithDeviation(const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& points,
                           const std::vector<double>& deviation_mm);

}  // namespace waam::analysis
