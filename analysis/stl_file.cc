// Reading an STL file for the planner's parser.
#include "analysis/stl_file.h"

#include "models/core/files.h"
#include "planner/mesh/stl_io.h"

namespace waam::analysis {

planner::TriangleMesh ReadStl(const std::filesystem::path& path, double weld_tolerance_mm, planner::MeshReport* report) {
  return planner::ParseStl(ReadFile(path), path, weld_tolerance_mm, report);
}

}  // namespace waam::analysis
