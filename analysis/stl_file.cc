// STL files: the bytes read for the planner's parser, and the binary and ASCII writers.
#include "analysis/stl_file.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

#include <Eigen/Geometry>

#include "models/core/error.h"
#include "models/core/files.h"
#include "planner/mesh/stl_io.h"

namespace waam::analysis {
namespace {

using planner::TriangleMesh;

constexpr std::size_t kFacetBytes = 50;  // normal, 3 vertices (float32 x 12) + uint16 attribute

void WriteOrThrow(std::ofstream& out, const std::filesystem::path& path) {
  out.close();
  if (out.fail()) ThrowOutputError(path, LastSystemError("the STL write failed"));
}

}  // namespace

planner::TriangleMesh ReadStl(const std::filesystem::path& path, double weld_tolerance_mm,
                              planner::MeshReport* report) {
  return planner::ParseStl(ReadFile(path), path, weld_tolerance_mm, report);
}

void WriteStlBinary(const TriangleMesh& mesh, const std::filesystem::path& path, const std::string& header_text) {
  WAAM_THROW_UNLESS(mesh.facets.size() <= planner::kMaxStlFacets,
                    path.string() << ": " << mesh.facets.size() << " facets exceed the STL limit of "
                                  << planner::kMaxStlFacets);
  AtomicOutput output(path);
  {
    errno = 0;
    std::ofstream out(output.temp_path(), std::ios::binary | std::ios::trunc);
    if (!out.is_open()) ThrowOutputError(path, LastSystemError("cannot open for writing"));
    char header[80] = {};
    std::memcpy(header, header_text.data(), std::min<std::size_t>(header_text.size(), sizeof(header)));
    out.write(header, sizeof(header));
    const auto count = static_cast<std::uint32_t>(mesh.facets.size());
    out.write(reinterpret_cast<const char*>(&count), sizeof(count));
    // Streamed in chunks, so a large part's STL never has to fit in memory next to its mesh.
    constexpr std::size_t kChunkFacets = 1 << 16;
    std::vector<char> buffer;
    buffer.reserve(kFacetBytes * std::min(kChunkFacets, mesh.facets.size()));
    for (std::size_t i = 0; i < mesh.facets.size(); ++i) {
      const std::array<int, 3>& f = mesh.facets[i];
      const Eigen::Vector3d& a = mesh.vertices[f[0]];
      const Eigen::Vector3d& b = mesh.vertices[f[1]];
      const Eigen::Vector3d& c = mesh.vertices[f[2]];
      Eigen::Vector3d n = (b - a).cross(c - a);
      if (n.norm() > 0.0) n.normalize();
      float values[12];
      for (int k = 0; k < 3; ++k) {
        values[k] = static_cast<float>(n[k]);
        values[3 + k] = static_cast<float>(a[k]);
        values[6 + k] = static_cast<float>(b[k]);
        values[9 + k] = static_cast<float>(c[k]);
      }
      const char* bytes = reinterpret_cast<const char*>(values);
      buffer.insert(buffer.end(), bytes, bytes + sizeof(values));
      buffer.push_back(0);  // attribute byte count
      buffer.push_back(0);
      if (buffer.size() >= kFacetBytes * kChunkFacets || i + 1 == mesh.facets.size()) {
        out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        buffer.clear();
      }
    }
    WriteOrThrow(out, path);
  }
  output.Commit();
}

void WriteStlAscii(const TriangleMesh& mesh, const std::filesystem::path& path, const std::string& name) {
  AtomicOutput output(path);
  errno = 0;
  std::ofstream out(output.temp_path(), std::ios::trunc);
  if (!out.is_open()) ThrowOutputError(path, LastSystemError("cannot open for writing"));
  out.precision(9);
  out << "solid " << name << "\n";
  for (const std::array<int, 3>& f : mesh.facets) {
    const Eigen::Vector3d& a = mesh.vertices[f[0]];
    const Eigen::Vector3d& b = mesh.vertices[f[1]];
    const Eigen::Vector3d& c = mesh.vertices[f[2]];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() > 0.0) n.normalize();
    out << "  facet normal " << n.x() << " " << n.y() << " " << n.z() << "\n    outer loop\n";
    for (const Eigen::Vector3d* v : {&a, &b, &c}) {
      out << "      vertex " << v->x() << " " << v->y() << " " << v->z() << "\n";
    }
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid " << name << "\n";
  WriteOrThrow(out, path);
  output.Commit();
}

}  // namespace waam::analysis
