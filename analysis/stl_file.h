// STL files: reading one (its bytes parsed and welded by planner::ParseStl) and writing a mesh as binary or ASCII STL.
#pragma once

#include <filesystem>
#include <string>

#include "planner/mesh/mesh_ops.h"
#include "planner/mesh/triangle_mesh.h"

namespace waam::analysis {

// Reads the binary or ASCII STL file `path` (mm) and parses it with planner::ParseStl: vertices within
// `weld_tolerance_mm` (0 to 10 mm) merged, `*report` (may be null) filled. Throws InputError naming the file when it
// is missing or unreadable, and as ParseStl does for its content.
planner::TriangleMesh ReadStl(const std::filesystem::path& path, double weld_tolerance_mm, planner::MeshReport* report);

// Writes `mesh` (mm) as binary STL (float32, facet normals from the vertex order, `header_text` cut to 80 bytes)
// atomically. Throws InputError when the mesh has more than planner::kMaxStlFacets facets, OutputError naming the
// path and the reason when the file cannot be written.
void WriteStlBinary(const planner::TriangleMesh& mesh, const std::filesystem::path& path,
                    const std::string& header_text = "binary STL written by waam-twin, millimetres");

// Writes `mesh` (mm) as ASCII STL ("solid <name>") atomically, with 9 significant digits. Throws OutputError naming
// the path and the reason when the file cannot be written.
void WriteStlAscii(const planner::TriangleMesh& mesh, const std::filesystem::path& path, const std::string& name);

}  // namespace waam::analysis
