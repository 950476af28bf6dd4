// Point-cloud files: strict PLY and XYZ readers that name the file and the line of the first problem, the PLY writer.
#include "analysis/point_cloud_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "models/core/error.h"
#include "models/core/files.h"
#include "planner/mesh/stl_io.h"
#include "twin/scanner/surface_sample.h"

namespace waam::analysis {
namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

void CheckPoint(const Eigen::Vector3d& p, const std::filesystem::path& path, const std::string& place) {
  WAAM_THROW_UNLESS(p.allFinite() && p.cwiseAbs().maxCoeff() <= planner::kMaxStlCoordinateMm,
                    path.string() << ": " << place << ": coordinate (" << p.x() << ", " << p.y() << ", " << p.z()
                    << ") is not finite or beyond " << planner::kMaxStlCoordinateMm << " mm");
}

std::vector<Eigen::Vector3d> ReadXyz(const std::filesystem::path& path) {
  std::ifstream in(path);
  WAAM_THROW_UNLESS(in, path.string() << ": cannot open the scan file");
  std::vector<Eigen::Vector3d> points;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    for (char& c : line) {
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    }
    if (line.find_first_not_of(' ') == std::string::npos) continue;
    std::istringstream fields(line);
    Eigen::Vector3d p;
    WAAM_THROW_UNLESS(fields >> p.x() >> p.y() >> p.z(),
                      path.string() << ":" << number << ": expected three numbers x y z (mm), got '" << line << "'");
    CheckPoint(p, path, "line " + std::to_string(number));
    WAAM_THROW_UNLESS(points.size() < kMaxScanPoints,
                      path.string() << ":" << number << ": more than " << kMaxScanPoints << " points");
    points.push_back(p);
  }
  WAAM_THROW_UNLESS(!points.empty(), path.string() << ": no points in the XYZ file");
  return points;
}

struct PlyProperty {
  std::string name;
  std::string type;
  bool list = false;
};

int TypeSize(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

double ReadBinary(const char* p, const std::string& t) {
  auto get = [&](auto v) {
    std::memcpy(&v, p, sizeof(v));
    return static_cast<double>(v);
  };
  if (t == "char" || t == "int8") return get(std::int8_t{});
  if (t == "uchar" || t == "uint8") return get(std::uint8_t{});
  if (t == "short" || t == "int16") return get(std::int16_t{});
  if (t == "ushort" || t == "uint16") return get(std::uint16_t{});
  if (t == "int" || t == "int32") return get(std::int32_t{});
  if (t == "uint" || t == "uint32") return get(std::uint32_t{});
  if (t == "float" || t == "float32") return get(float{});
  return get(double{});
}

// A PLY file's bytes read line by line (the header, an ASCII body) or as binary values, with the line count.
struct PlyText {
  std::string data;
  std::size_t pos = 0;
  std::size_t line_no = 0;

  // The next line without its end ('\n' or "\r\n"); false at the end of the data.
  bool NextLine(std::string* line) {
    if (pos >= data.size()) return false;
    std::size_t end = data.find('\n', pos);
    if (end == std::string::npos) end = data.size();
    *line = data.substr(pos, end - pos);
    if (!line->empty() && line->back() == '\r') line->pop_back();
    pos = end + 1;
    ++line_no;
    return true;
  }
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> props;
};

struct PlyHeader {
  std::string format;  // ascii | binary_little_endian
  std::vector<PlyElement> elements;
};

// `property <type> <name>` or `property list <count type> <item type> <name>`, after the word `property`.
PlyProperty ReadPlyProperty(std::istringstream& f, const std::string& where) {
  PlyProperty p;
  std::string t;
  f >> t;
  if (t == "list") {
    std::string count_type, item_type;
    f >> count_type >> item_type >> p.name;
    WAAM_THROW_UNLESS(TypeSize(count_type) > 0 && TypeSize(item_type) > 0,
                      where << ": unknown list type '" << count_type << " " << item_type << "'");
    p.list = true;
    p.type = count_type + " " + item_type;
  } else {
    WAAM_THROW_UNLESS(TypeSize(t) > 0, where << ": unknown property type '" << t << "'");
    f >> p.name;
    p.type = t;
  }
  return p;
}

// The header from `ply` to `end_header`: the format and the elements with their properties.
PlyHeader ReadPlyHeader(PlyText& text, const std::filesystem::path& path) {
  std::string line;
  WAAM_THROW_UNLESS(text.NextLine(&line) && line == "ply",
                    path.string() << ":1: not a PLY file (first line must be 'ply')");
  PlyHeader header;
  bool header_done = false;
  while (text.NextLine(&line)) {
    std::istringstream f(line);
    std::string word;
    f >> word;
    const std::string where = path.string() + ":" + std::to_string(text.line_no);
    if (word == "format") {
      std::string version;
      f >> header.format >> version;
      WAAM_THROW_UNLESS(header.format == "ascii" || header.format == "binary_little_endian",
                        where << ": PLY format '" << header.format
                              << "' not supported: must be ascii or binary_little_endian");
    } else if (word == "comment" || word == "obj_info" || word.empty()) {
    } else if (word == "element") {
      PlyElement e;
      long long count = -1;
      WAAM_THROW_UNLESS(f >> e.name >> count && count >= 0, where << ": expected 'element <name> <count>'");
      e.count = static_cast<std::size_t>(count);
      header.elements.push_back(e);
    } else if (word == "property") {
      WAAM_THROW_UNLESS(!header.elements.empty(), where << ": property before any element");
      header.elements.back().props.push_back(ReadPlyProperty(f, where));
    } else if (word == "end_header") {
      header_done = true;
      break;
    } else {
      WAAM_THROW_UNLESS(false, where << ": unexpected header keyword '" << word << "'");
    }
  }
  WAAM_THROW_UNLESS(header_done, path.string() << ": PLY header has no end_header");
  WAAM_THROW_UNLESS(!header.format.empty(), path.string() << ": PLY header has no format line");
  return header;
}

// The indices of an element's x, y and z properties (-1: none); a vertex element must have all three as scalars.
struct PlyXyz {
  int ix = -1, iy = -1, iz = -1;
  // Stores `v`, the value of property k, into `value` when k is x, y or z.
  void Keep(std::size_t k, double v, double value[3]) const {
    if (static_cast<int>(k) == ix) value[0] = v;
    if (static_cast<int>(k) == iy) value[1] = v;
    if (static_cast<int>(k) == iz) value[2] = v;
  }
};

PlyXyz FindXyz(const PlyElement& e) {
  PlyXyz xyz;
  for (std::size_t k = 0; k < e.props.size(); ++k) {
    if (e.props[k].name == "x") xyz.ix = static_cast<int>(k);
    if (e.props[k].name == "y") xyz.iy = static_cast<int>(k);
    if (e.props[k].name == "z") xyz.iz = static_cast<int>(k);
  }
  return xyz;
}

// Item n of element e in an ASCII body: one line; x, y, z (where e has them) into `value`.
void ReadAsciiItem(PlyText& text, const PlyElement& e, const PlyXyz& xyz, std::size_t n,
                   const std::filesystem::path& path, double value[3]) {
  std::string line;
  WAAM_THROW_UNLESS(text.NextLine(&line), path.string() << ": PLY ends in element " << e.name << " " << n << " of "
                                                        << e.count << " (line " << text.line_no + 1 << ")");
  std::istringstream f(line);
  for (std::size_t k = 0; k < e.props.size(); ++k) {
    double v = 0;
    if (e.props[k].list) {
      long long count = 0;
      WAAM_THROW_UNLESS(f >> count && count >= 0, path.string() << ":" << text.line_no << ": bad list count");
      for (long long c = 0; c < count; ++c) {
        WAAM_THROW_UNLESS(f >> v, path.string() << ":" << text.line_no << ": list shorter than its count");
      }
      continue;
    }
    WAAM_THROW_UNLESS(f >> v, path.string() << ":" << text.line_no << ": expected " << e.props.size()
                                            << " values of element " << e.name << ", got '" << line << "'");
    xyz.Keep(k, v, value);
  }
}

// Item n of element e in a binary little-endian body; x, y, z (where e has them) into `value`.
void ReadBinaryItem(PlyText& text, const PlyElement& e, const PlyXyz& xyz, std::size_t n,
                    const std::filesystem::path& path, double value[3]) {
  const std::string& data = text.data;
  std::size_t& pos = text.pos;
  for (std::size_t k = 0; k < e.props.size(); ++k) {
    const PlyProperty& p = e.props[k];
    if (p.list) {
      const std::string count_type = p.type.substr(0, p.type.find(' '));
      const std::string item_type = p.type.substr(p.type.find(' ') + 1);
      WAAM_THROW_UNLESS(pos + TypeSize(count_type) <= data.size(),
                        path.string() << ": binary PLY truncated in element " << e.name << " " << n);
      const double count = ReadBinary(data.data() + pos, count_type);
      pos += TypeSize(count_type);
      WAAM_THROW_UNLESS(count >= 0 && pos + count * TypeSize(item_type) <= data.size(),
                        path.string() << ": binary PLY truncated in element " << e.name << " " << n);
      pos += static_cast<std::size_t>(count) * TypeSize(item_type);
      continue;
    }
    WAAM_THROW_UNLESS(pos + TypeSize(p.type) <= data.size(),
                      path.string() << ": binary PLY truncated at " << e.name << " " << n << " of " << e.count);
    const double v = ReadBinary(data.data() + pos, p.type);
    pos += TypeSize(p.type);
    xyz.Keep(k, v, value);
  }
}

std::vector<Eigen::Vector3d> ReadPly(const std::filesystem::path& path) {
  PlyText text{ReadFile(path)};
  const PlyHeader header = ReadPlyHeader(text, path);
  const bool ascii = header.format == "ascii";
  std::vector<Eigen::Vector3d> points;
  bool found_vertex = false;
  for (const PlyElement& e : header.elements) {
    const PlyXyz xyz = FindXyz(e);
    const bool is_vertex = e.name == "vertex";
    if (is_vertex) {
      found_vertex = true;
      WAAM_THROW_UNLESS(xyz.ix >= 0 && xyz.iy >= 0 && xyz.iz >= 0 && !e.props[xyz.ix].list &&
                            !e.props[xyz.iy].list && !e.props[xyz.iz].list,
                        path.string() << ": PLY element vertex needs scalar properties x, y and z");
      WAAM_THROW_UNLESS(e.count <= kMaxScanPoints,
                        path.string() << ": PLY declares " << e.count << " vertices, more than " << kMaxScanPoints);
      points.reserve(e.count);
    }
    for (std::size_t n = 0; n < e.count; ++n) {
      double value[3] = {0, 0, 0};
      if (ascii) {
        ReadAsciiItem(text, e, xyz, n, path, value);
      } else {
        ReadBinaryItem(text, e, xyz, n, path, value);
      }
      if (!is_vertex) continue;
      const Eigen::Vector3d p(value[0], value[1], value[2]);
      CheckPoint(p, path, ascii ? "line " + std::to_string(text.line_no) : "vertex " + std::to_string(n));
      points.push_back(p);
    }
  }
  WAAM_THROW_UNLESS(found_vertex && !points.empty(), path.string() << ": PLY has no vertex element or no vertices");
  return points;
}

}  // namespace

std::vector<Eigen::Vector3d> ReadPointCloud(const std::filesystem::path& path, double stl_spacing_mm) {
  const std::string ext = Lower(path.extension().string());
  if (ext == ".ply") return ReadPly(path);
  if (ext == ".xyz" || ext == ".txt" || ext == ".asc") return ReadXyz(path);
  if (ext == ".stl") return twin::SampleSurface(planner::ParseStl(ReadFile(path), path, 0.0, nullptr), stl_spacing_mm);
  WAAM_THROW(path.string() << ": unknown scan format '" << ext << "': must be .ply, .xyz or .stl");
}

ScanCloud ReadScan(const std::filesystem::path& path, double stl_spacing_mm, bool skip_bottom) {
  ScanCloud cloud;
  if (Lower(path.extension().string()) != ".stl") {
    cloud.points = ReadPointCloud(path, stl_spacing_mm);
    cloud.weight.assign(cloud.points.size(), 1.0);
    return cloud;
  }
  twin::SurfaceSamples samples =
      twin::SampleSurfaceByArea(planner::ParseStl(ReadFile(path), path, 0.0, nullptr), stl_spacing_mm, skip_bottom);
  WAAM_THROW_UNLESS(!samples.points.empty(), path.string() << ": STL has no facets to sample"
                                                           << (samples.skipped_facets > 0 ? " above its bottom face" : ""));
  cloud.points = std::move(samples.points);
  cloud.weight = std::move(samples.area_mm2);
  cloud.area_weighted = true;
  cloud.bottom_facets_skipped = samples.skipped_facets;
  cloud.bottom_area_skipped_mm2 = samples.skipped_area_mm2;
  return cloud;
}

void WritePlyWithDeviation(const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& points,
                           const std::vector<double>& deviation_mm) {
  WAAM_THROW_UNLESS(points.size() == deviation_mm.size(), "PLY writer: " << points.size() << " points but "
                                                                         << deviation_mm.size() << " deviations");
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment waam-twin scan, mm\nelement vertex " +
                    std::to_string(points.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nproperty float deviation_mm\nend_header\n";
  out.reserve(out.size() + 16 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const float v[4] = {static_cast<float>(points[i].x()), static_cast<float>(points[i].y()),
                        static_cast<float>(points[i].z()), static_cast<float>(deviation_mm[i])};
    out.append(reinterpret_cast<const char*>(v), sizeof(v));
  }
  WriteFileAtomic(path, out);
}

}  // namespace waam::analysis
