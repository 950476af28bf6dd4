// STL parser (binary and ASCII, with welding and validation); the writers are analysis/stl_file.h's.
#include "planner/mesh/stl_io.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "models/core/error.h"
#include "models/core/json_text.h"

namespace waam::planner {
namespace {

static_assert(std::endian::native == std::endian::little, "the binary STL reader assumes a little-endian host");

constexpr std::size_t kHeaderBytes = 84;  // 80-byte header + uint32 facet count
constexpr std::size_t kFacetBytes = 50;   // normal, 3 vertices (float32 x 12) + uint16 attribute

std::string Name(const std::filesystem::path& path) { return path.string(); }

std::vector<Eigen::Vector3d> ParseBinary(const std::string& data, std::uint64_t count,
                                         const std::filesystem::path& path) {
  std::vector<Eigen::Vector3d> corners;
  corners.reserve(count * 3);
  for (std::uint64_t f = 0; f < count; ++f) {
    const char* facet = data.data() + kHeaderBytes + f * kFacetBytes;
    for (int v = 0; v < 3; ++v) {
      float xyz[3];
      std::memcpy(xyz, facet + 12 + 12 * v, sizeof(xyz));
      for (int a = 0; a < 3; ++a) {
        WAAM_THROW_UNLESS(std::isfinite(xyz[a]), Name(path) << ": binary STL facet " << f + 1 << " of " << count
                                                            << ": vertex " << v + 1 << " has a non-finite coordinate ("
                                                            << xyz[a] << "); coordinates must be finite numbers");
        WAAM_THROW_UNLESS(std::abs(xyz[a]) <= kMaxStlCoordinateMm,
                          Name(path) << ": binary STL facet " << f + 1 << " of " << count << ": vertex " << v + 1
                                     << " coordinate " << xyz[a] << " mm is beyond +-" << kMaxStlCoordinateMm
                                     << " mm (corrupt file or wrong units?)");
      }
      corners.emplace_back(xyz[0], xyz[1], xyz[2]);
    }
  }
  return corners;
}

// A whitespace-separated token of an ASCII STL and the 1-based line it starts on.
class AsciiTokens {
 public:
  AsciiTokens(const std::string& data, const std::filesystem::path& path) : data_(data), path_(path) {}

  // Next token, or an empty view at the end of the file.
  std::string_view Next() {
    while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) {
      if (data_[pos_] == '\n') ++line_;
      ++pos_;
    }
    token_line_ = line_;
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    return std::string_view(data_).substr(start, pos_ - start);
  }

  // Skips to the end of the current line (the name after "solid"/"endsolid").
  void SkipLine() {
    while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
  }

  void Expect(std::string_view keyword, std::string_view context) {
    const std::string_view token = Next();
    WAAM_THROW_UNLESS(Is(token, keyword), Where() << ": expected '" << keyword << "' " << context << ", found "
                                                  << Shown(token));
  }

  double Number(std::string_view what) {
    std::string_view token = Next();
    WAAM_THROW_UNLESS(!token.empty(), Where() << ": expected a number for " << what << ", found the end of file");
    std::string_view digits = token;
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    WAAM_THROW_UNLESS(ec == std::errc() && end == digits.data() + digits.size(),
                      Where() << ": expected a number for " << what << ", found '" << token << "'");
    WAAM_THROW_UNLESS(std::isfinite(value), Where() << ": " << what << " '" << token
                                                    << "' is not finite; coordinates must be finite numbers");
    WAAM_THROW_UNLESS(std::abs(value) <= kMaxStlCoordinateMm, Where() << ": " << what << " " << value
                                                                      << " mm is beyond +-" << kMaxStlCoordinateMm
                                                                      << " mm (corrupt file or wrong units?)");
    return value;
  }

  static bool Is(std::string_view token, std::string_view keyword) {
    return token.size() == keyword.size() &&
           std::equal(token.begin(), token.end(), keyword.begin(), [](char a, char b) {
             return std::tolower(static_cast<unsigned char>(a)) == b;
           });
  }

  static std::string Shown(std::string_view token) {
    if (token.empty()) return "the end of file";
    std::string shown(1, '\'');
    shown.append(token.substr(0, 40));
    shown.push_back('\'');
    return shown;
  }

  std::string Where() const { return Name(path_) + ": ASCII STL line " + std::to_string(token_line_); }

 private:
  const std::string& data_;
  const std::filesystem::path& path_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
  std::size_t token_line_ = 1;
};

std::vector<Eigen::Vector3d> ParseAscii(const std::string& data, const std::filesystem::path& path) {
  AsciiTokens tokens(data, path);
  std::vector<Eigen::Vector3d> corners;
  tokens.Expect("solid", "at the start of an ASCII STL");
  tokens.SkipLine();
  std::size_t facets = 0;
  // Several solids may follow each other; a missing final "endsolid" is tolerated.
  for (std::string_view token = tokens.Next(); !token.empty(); token = tokens.Next()) {
    if (AsciiTokens::Is(token, "endsolid")) {
      tokens.SkipLine();
      token = tokens.Next();
      if (token.empty()) break;
      WAAM_THROW_UNLESS(AsciiTokens::Is(token, "solid"),
                        tokens.Where() << ": expected 'solid' or the end of file after 'endsolid', found "
                                       << AsciiTokens::Shown(token));
      tokens.SkipLine();
      continue;
    }
    WAAM_THROW_UNLESS(AsciiTokens::Is(token, "facet"),
                      tokens.Where() << ": expected 'facet' or 'endsolid', found " << AsciiTokens::Shown(token));
    ++facets;
    WAAM_THROW_UNLESS(facets <= kMaxStlFacets, tokens.Where() << ": more than " << kMaxStlFacets
                                                              << " facets; decimate the mesh first");
    tokens.Expect("normal", "after 'facet'");
    // The stored normal is not used (it is recomputed from the vertex order) but must be three numbers.
    for (int a = 0; a < 3; ++a) {
      std::string_view n = tokens.Next();
      double ignored = 0.0;
      std::string_view digits = n;
      if (!digits.empty() && (digits.front() == '+')) digits.remove_prefix(1);
      const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), ignored);
      WAAM_THROW_UNLESS(!n.empty() && ec == std::errc() && end == digits.data() + digits.size(),
                        tokens.Where() << ": expected a number for the facet normal, found " << AsciiTokens::Shown(n));
    }
    tokens.Expect("outer", "after the facet normal");
    tokens.Expect("loop", "after 'outer'");
    for (int v = 0; v < 3; ++v) {
      tokens.Expect("vertex", "(a facet needs exactly 3 vertices)");
      const double x = tokens.Number("vertex x");
      const double y = tokens.Number("vertex y");
      const double z = tokens.Number("vertex z");
      corners.emplace_back(x, y, z);
    }
    tokens.Expect("endloop", "after the third vertex (a facet needs exactly 3 vertices)");
    tokens.Expect("endfacet", "after 'endloop'");
  }
  return corners;
}

bool StartsWithSolid(const std::string& data) {
  std::size_t i = 0;
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  return data.size() - i >= 5 && AsciiTokens::Is(std::string_view(data).substr(i, 5), "solid");
}

}  // namespace

TriangleMesh ParseStl(const std::string& data, const std::filesystem::path& path, double weld_tolerance_mm,
                      MeshReport* report) {
  WAAM_THROW_UNLESS(std::isfinite(weld_tolerance_mm) && weld_tolerance_mm >= 0.0 && weld_tolerance_mm <= 10.0,
                    Name(path) << ": weld tolerance " << weld_tolerance_mm << " mm: must be between 0 and 10 mm");
  WAAM_THROW_UNLESS(!data.empty(), Name(path) << ": the file is empty (0 bytes); expected a binary or ASCII STL");

  std::uint64_t header_count = 0;
  if (data.size() >= kHeaderBytes) {
    std::uint32_t count32 = 0;
    std::memcpy(&count32, data.data() + 80, sizeof(count32));
    header_count = count32;
  }
  const std::uint64_t expected_size = kHeaderBytes + kFacetBytes * header_count;
  // Binary by the size rule; a file that starts with "solid" but holds NUL bytes is a damaged binary file.
  const bool has_nul = std::memchr(data.data(), '\0', std::min<std::size_t>(data.size(), 4096)) != nullptr;
  const bool binary = (data.size() >= kHeaderBytes && expected_size == data.size()) || !StartsWithSolid(data) ||
                      (has_nul && data.size() >= kHeaderBytes);

  std::vector<Eigen::Vector3d> corners;
  if (binary) {
    WAAM_THROW_UNLESS(data.size() >= kHeaderBytes,
                      Name(path) << ": " << data.size() << " bytes is shorter than the 84-byte binary STL header, "
                                 << "and the file does not start with 'solid' (ASCII STL)");
    WAAM_THROW_UNLESS(header_count <= kMaxStlFacets,
                      Name(path) << ": binary STL header claims " << header_count << " facets, more than the limit of "
                                 << kMaxStlFacets << " (corrupt header, or decimate the mesh first)");
    if (data.size() < expected_size) {
      const std::uint64_t complete = (data.size() - kHeaderBytes) / kFacetBytes;
      const bool mid_facet = (data.size() - kHeaderBytes) % kFacetBytes != 0;
      WAAM_THROW(Name(path) << ": truncated binary STL: header says " << header_count << " facets (" << expected_size
                            << " bytes) but the file has " << data.size() << " bytes; "
                            << (mid_facet ? "it ends inside facet " + std::to_string(complete + 1)
                                          : "it ends after facet " + std::to_string(complete)));
    }
    WAAM_THROW_UNLESS(data.size() == expected_size,
                      Name(path) << ": binary STL header facet count " << header_count << " disagrees with the file size "
                                 << data.size() << " bytes (expected 84 + 50 x " << header_count << " = "
                                 << expected_size << " bytes)");
    corners = ParseBinary(data, header_count, path);
  } else {
    corners = ParseAscii(data, path);
  }

  const std::size_t read = corners.size() / 3;
  std::size_t degenerate = 0;
  TriangleMesh mesh = WeldTriangles(corners, weld_tolerance_mm, &degenerate);
  WAAM_THROW_UNLESS(!mesh.facets.empty(), Name(path) << ": no usable facet: " << read << " facets read, " << degenerate
                                                     << " degenerate (zero area or repeated vertex after welding at "
                                                     << weld_tolerance_mm << " mm)");
  if (report) {
    *report = InspectMesh(mesh, weld_tolerance_mm, Name(path));
    report->binary = binary;
    report->facets_read = read;
    report->degenerate_facets = degenerate;
    report->facets = mesh.facets.size();
  }
  return mesh;
}

void CheckSliceable(const MeshReport& report) {
  WAAM_THROW_UNLESS(report.facets > 0, report.source << ": the mesh has no facets; nothing to slice");
  if (report.boundary_edges == 0 && report.non_manifold_edges == 0) return;
  std::ostringstream problems;
  if (report.boundary_edges > 0) {
    problems << "the mesh is open: " << report.boundary_edges << " boundary edges (used by one facet)";
  }
  if (report.non_manifold_edges > 0) {
    problems << (report.boundary_edges > 0 ? " and " : "the mesh has ") << report.non_manifold_edges
             << " non-manifold edges (used by more than two facets)";
  }
  WAAM_THROW(report.source << ": " << problems.str() << " after welding at " << report.weld_tolerance_mm
                           << " mm; slicing needs a closed manifold surface (repair the mesh"
                           << (report.non_manifold_edges == 0 ? " or raise the weld tolerance)" : ")"));
}

std::string MeshReportJson(const MeshReport& report) {
  std::string reason;
  try {
    CheckSliceable(report);
  } catch (const InputError& e) {
    reason = e.what();
  }
  const nlohmann::json json = {
      {"source", report.source},
      {"binary", report.binary},
      {"facets_read", report.facets_read},
      {"facets", report.facets},
      {"vertices", report.vertices},
      {"degenerate_facets", report.degenerate_facets},
      {"boundary_edges", report.boundary_edges},
      {"non_manifold_edges", report.non_manifold_edges},
      {"misoriented_edges", report.misoriented_edges},
      {"watertight", report.watertight},
      {"volume_mm3", report.volume_mm3},
      {"bbox_min_mm", {report.bbox_min.x(), report.bbox_min.y(), report.bbox_min.z()}},
      {"bbox_max_mm", {report.bbox_max.x(), report.bbox_max.y(), report.bbox_max.z()}},
      {"weld_tolerance_mm", report.weld_tolerance_mm},
      {"sliceable", reason.empty()},
      {"not_sliceable_reason", reason},
  };
  return JsonText(json);
}

}  // namespace waam::planner
