// Reading an STL file: its bytes read here, parsed and welded by planner::ParseStl.
#pragma once

#include <filesystem>

#include "planner/mesh/mesh_ops.h"
#include "planner/mesh/triangle_mesh.h"

namespace waam::analysis {

// Reads the binary or ASCII STL file `path` (mm) and parses it with planner::ParseStl: vertices within
// `weld_tolerance_mm` (0 to 10 mm) merged, `*report` (may be null) filled. Throws InputError naming the file when it
// is missing or unreadable, and as ParseStl does for its content.
planner::TriangleMesh ReadStl(const std::filesystem::path& path, double weld_tolerance_mm, planner::MeshReport* report);

}  // namespace waam::analysis
