// The cell's files read for the twin: MJCF with its assets (meshes, textures, includes), URDF with its meshes.
#include "analysis/cell_files.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include <tinyxml2.h>

#include "models/core/data_dir.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/cell_presets.h"
#include "twin/cell/urdf_arm.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The assets of one MJCF model, gathered from the model file and the files it includes.
class MjcfAssets {
 public:
  explicit MjcfAssets(const fs::path& model) : dir_(model.parent_path()) {}

  // The compiler's folders (meshdir, texturedir, assetdir) wherever its element stands in `e`.
  void Folders(const tinyxml2::XMLElement* e) {
    if (std::string(e->Name()) == "compiler") {
      for (const char* key : {"meshdir", "texturedir", "assetdir"}) {
        if (const char* v = e->Attribute(key)) dirs_[key] = v;
      }
    }
    for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) Folders(c);
  }

  // Every file element `e` of `file` (and its children) names, read into `out`.
  void Collect(const tinyxml2::XMLElement* e, const fs::path& file, twin::MjcfSource* out) {
    const std::string tag = e->Name();
    static const char* const kTextureFiles[] = {"file",     "fileright", "fileleft", "fileup",
                                                "filedown", "filefront", "fileback"};
    if (tag == "mesh" || tag == "skin" || tag == "hfield") {
      Add(e, "file", "meshdir", file, out);
    } else if (tag == "texture") {
      for (const char* key : kTextureFiles) Add(e, key, "texturedir", file, out);
    } else if (tag == "include") {
      const fs::path included = Add(e, "file", "", file, out);
      if (!included.empty()) {
        // The included MJCF names files of its own.
        tinyxml2::XMLDocument doc;
        if (doc.Parse(out->assets.back().second.data(), out->assets.back().second.size()) ==
                tinyxml2::XML_SUCCESS &&
            doc.RootElement()) {
          Collect(doc.RootElement(), included, out);
        }
      }
    }
    for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      Collect(c, file, out);
    }
  }

 private:
  // Reads the file that attribute `key` of `e` names (found under the compiler's `dir_key` folder, the assetdir or
  // beside the model) into `out`, once per file; returns its path (empty when `e` has no such attribute or the file
  // was read before).
  fs::path Add(const tinyxml2::XMLElement* e, const char* key, const std::string& dir_key, const fs::path& file,
               twin::MjcfSource* out) {
    const char* value = e->Attribute(key);
    if (!value || !*value) return {};
    const std::string where = file.string() + ":" + std::to_string(e->GetLineNum()) + ": <" + e->Name() + " " + key +
                              "=\"" + value + "\">: ";
    const fs::path name(value);
    std::vector<fs::path> candidates;
    if (name.is_absolute()) {
      candidates.push_back(name);
    } else {
      for (const std::string& d : {dir_key, std::string("assetdir")}) {
        if (!d.empty() && dirs_.count(d)) candidates.push_back(dir_ / dirs_.at(d) / name);
      }
      candidates.push_back(dir_ / name);
    }
    std::error_code ec;
    const auto found = std::find_if(candidates.begin(), candidates.end(),
                                    [&](const fs::path& p) { return fs::is_regular_file(p, ec); });
    if (found == candidates.end()) {
      std::string looked;
      for (const fs::path& p : candidates) looked += (looked.empty() ? "" : ", ") + p.string();
      WAAM_THROW(where << "file not found (looked for " << looked << ")");
    }
    const fs::path path = found->lexically_normal();
    const std::string base = Lower(name.filename().string());
    const auto seen = seen_.find(base);
    if (seen != seen_.end()) {
      WAAM_THROW_UNLESS(seen->second == path, where << "names " << path.string() << ", and another element names "
                                                    << seen->second.string() << ": MuJoCo finds files by name, "
                                                    << "without their folders, in any case; rename one");
      return {};
    }
    seen_[base] = path;
    out->assets.emplace_back(value, ReadFile(path));
    return path;
  }

  fs::path dir_;  // the model's folder
  std::map<std::string, std::string> dirs_;  // the compiler's meshdir, texturedir, assetdir
  std::map<std::string, fs::path> seen_;     // lower-case file name -> the file read under it
};

// Where a URDF's mesh URI points: package://NAME/rest, file://path, absolute, or relative to the URDF.
fs::path ResolveMesh(const twin::CellSettings& settings, const std::string& where, const std::string& uri) {
  std::error_code ec;
  const std::string pkg_prefix = "package://";
  if (uri.rfind(pkg_prefix, 0) == 0) {
    const std::string rest = uri.substr(pkg_prefix.size());
    const std::size_t slash = rest.find('/');
    WAAM_THROW_UNLESS(slash != std::string::npos && slash > 0, where << "mesh '" << uri << "': no package name");
    const std::string package = rest.substr(0, slash);
    const std::string inside = rest.substr(slash + 1);
    std::vector<fs::path> dirs = settings.robot_package_paths;
    if (const char* ros = std::getenv("ROS_PACKAGE_PATH")) {
      std::stringstream in(ros);
      std::string d;
      while (std::getline(in, d, ':')) {
        if (!d.empty()) dirs.emplace_back(d);
      }
    }
    std::string searched;
    for (const fs::path& dir : dirs) {
      // DIR/NAME/rest; a ROS_PACKAGE_PATH entry may also be the package itself.
      for (const fs::path& pkg_dir : {dir / package, dir.filename() == package ? dir : fs::path()}) {
        if (pkg_dir.empty()) continue;
        if (fs::is_directory(pkg_dir, ec)) {
          const fs::path f = pkg_dir / inside;
          WAAM_THROW_UNLESS(fs::is_regular_file(f, ec), where << "mesh " << f.string() << " not found");
          return f;
        }
      }
      searched += (searched.empty() ? "" : ", ") + dir.string();
    }
    WAAM_THROW(where << "unknown package '" << package << "' of mesh '" << uri << "': searched "
                     << (searched.empty() ? std::string("no directory") : searched)
                     << " (cell.robot.package_paths, then ROS_PACKAGE_PATH)");
  }
  fs::path f = uri.rfind("file://", 0) == 0 ? fs::path(uri.substr(7)) : fs::path(uri);
  if (f.is_relative()) f = settings.robot_urdf.parent_path() / f;
  WAAM_THROW_UNLESS(fs::is_regular_file(f, ec), where << "mesh " << f.string() << " not found");
  return f;
}

// The bytes of a URDF's collision mesh, checked as MuJoCo 2.2 reads meshes.
std::string ReadUrdfMesh(const twin::CellSettings& settings, const twin::UrdfMesh& mesh) {
  const std::string where = settings.robot_urdf.string() + ":" + std::to_string(mesh.line) + ": ";
  const fs::path file = ResolveMesh(settings, where, mesh.uri);
  const std::string ext = Lower(file.extension().string());
  WAAM_THROW_UNLESS(ext == ".stl" || ext == ".obj",
                    where << "mesh " << file.string() << ": MuJoCo 2.2 reads STL and OBJ, not " << ext
                          << " (convert the collision mesh once, e.g. with meshlab)");
  std::string bytes = ReadFile(file);
  if (ext == ".stl") {
    // MuJoCo 2.2 reads binary STL only: 80-byte header, facet count, 50 bytes per facet.
    std::uint32_t facets = 0;
    if (bytes.size() >= 84) std::memcpy(&facets, bytes.data() + 80, 4);
    WAAM_THROW_UNLESS(bytes.size() >= 84 && bytes.size() == 84 + 50 * static_cast<std::uint64_t>(facets) && facets > 0,
                      where << "mesh " << file.string()
                            << " is not a binary STL (an ASCII STL?): MuJoCo 2.2 reads binary STL only; convert it "
                               "once (e.g. meshlab, admesh -b)");
  }
  return bytes;
}

bool BuiltinCell(const twin::CellSettings& settings) {
  return settings.preset ? twin::PresetUrdf(*settings.preset).empty()
                         : settings.robot_urdf.empty() && settings.mjcf.empty();
}

}  // namespace

fs::path BuiltinCellPath() { return DataDir() / "twin" / "data" / "cell_arcmate100ic.xml"; }

twin::MjcfSource ReadMjcf(const fs::path& file) {
  twin::MjcfSource source;
  source.builtin = file.empty();
  source.file = source.builtin ? BuiltinCellPath() : file;
  std::error_code ec;
  WAAM_THROW_UNLESS(fs::is_regular_file(source.file, ec), source.file.string() << ": MJCF cell model not found");
  source.xml = ReadFile(source.file);
  tinyxml2::XMLDocument doc;
  if (doc.Parse(source.xml.data(), source.xml.size()) == tinyxml2::XML_SUCCESS && doc.RootElement()) {
    MjcfAssets assets(source.file);
    assets.Folders(doc.RootElement());
    assets.Collect(doc.RootElement(), source.file, &source);
  }
  return source;
}

twin::CellFiles ReadUrdfFiles(const twin::CellSettings& settings) {
  const fs::path& urdf = settings.robot_urdf;
  WAAM_THROW_UNLESS(urdf.extension() != ".xacro", urdf.string() << ": a .xacro file is not read; run `xacro "
                                                                << urdf.filename().string()
                                                                << " > arm.urdf` once and name the .urdf");
  std::error_code ec;
  WAAM_THROW_UNLESS(fs::is_regular_file(urdf, ec), urdf.string() << ": URDF file not found");
  twin::UrdfArmOptions options;
  options.joints = settings.robot_joints;
  options.flange = settings.robot_flange;
  twin::CellFiles files;
  files.arm = twin::ParseUrdfArm(ReadFile(urdf), urdf, options);
  files.arm_meshes.file = urdf;
  for (const twin::UrdfMesh& mesh : files.arm->meshes) {
    files.arm_meshes.assets.emplace_back(mesh.file, ReadUrdfMesh(settings, mesh));
  }
  return files;
}

twin::CellFiles ReadCellFiles(const twin::CellSettings& settings) {
  if (BuiltinCell(settings)) return {ReadMjcf({}), std::nullopt, {}};
  if (!settings.robot_urdf.empty()) return ReadUrdfFiles(settings);
  return {ReadMjcf(settings.mjcf), std::nullopt, {}};
}

twin::CellModel LoadCell(const twin::CellSettings& settings) {
  return twin::BuildCell(settings, ReadCellFiles(settings));
}

twin::CellModel LoadCellModel(const fs::path& file) { return twin::CellModel(ReadMjcf(file)); }

}  // namespace waam::analysis
