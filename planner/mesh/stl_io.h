// Parsing STL meshes (binary and ASCII) with welding and a health report (the file is read and written by
// analysis/stl_file.h).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "planner/mesh/mesh_ops.h"
#include "planner/mesh/triangle_mesh.h"

namespace waam::planner {

// Largest facet count accepted from a file (about 1 GB of binary STL). Larger parts should be decimated first;
// the limit keeps a corrupt header from making the reader allocate gigabytes.
inline constexpr std::size_t kMaxStlFacets = 20'000'000;

// Largest coordinate magnitude accepted from a file (mm): 1 km, far beyond any WAAM cell; larger values mean a
// corrupt file or wrong units.
inline constexpr double kMaxStlCoordinateMm = 1e6;

// Parses the bytes `data` of a binary or ASCII STL file `path` (coordinates in mm; the file is read by
// analysis::ReadStl, `path` names it in messages). A file is binary when its size is exactly
// 84 + 50 n bytes with n the facet count in its header (binary files may begin with "solid" too); otherwise it
// must be ASCII. Vertices within `weld_tolerance_mm` (0 to 10 mm; 0 welds only identical points) are merged,
// degenerate facets are dropped, and `*report` (may be null) is filled. Throws InputError naming the file and the
// place (facet number or line) for an empty file, a truncated or inconsistent binary file, a facet count above
// kMaxStlFacets, a NaN/inf coordinate or one beyond kMaxStlCoordinateMm, an ASCII syntax error, or a file with no usable facet.
TriangleMesh ParseStl(const std::string& data, const std::filesystem::path& path, double weld_tolerance_mm,
                      MeshReport* report);

// Throws InputError naming `report.source` if the mesh cannot be sliced into closed contours: no facets, open
// (boundary edges left after welding) or non-manifold edges. Misoriented facets are accepted (the slicer orients
// contours by nesting depth), as is a mesh whose volume is negative (inside out).
void CheckSliceable(const MeshReport& report);

// The report as a JSON object text (keys as the MeshReport fields; bbox as [x, y, z] in mm) plus "sliceable" and
// "not_sliceable_reason" (the CheckSliceable message, empty when sliceable), indented by 2.
std::string MeshReportJson(const MeshReport& report);

}  // namespace waam::planner
