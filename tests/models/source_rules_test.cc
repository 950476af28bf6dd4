// The house's rules on the sources themselves: no module names another module's `internal` namespace, no file
// includes a header of a layer above its own (models <- planner <- twin <- analysis <- app), and the planner and the
// twin neither read nor write a file (readers and writers are analysis/'s, called from there).
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace waam {
namespace {
namespace fs = std::filesystem;

// The modules in layer order (lowest first).
const std::vector<std::string> kModules = {"models", "planner", "twin", "analysis", "app"};

int LayerOf(const std::string& module) {
  for (std::size_t i = 0; i < kModules.size(); ++i) {
    if (kModules[i] == module) return static_cast<int>(i);
  }
  return -1;
}

// Every line of every .h/.cc file of `module` that matches `pattern`, as "file:line: text" with the match's first
// group.
struct Hit {
  std::string where;
  std::string group;
};
std::vector<Hit> Grep(const std::string& module, const std::regex& pattern) {
  std::vector<Hit> hits;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(WAAM_SOURCE_DIR) / module)) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() || (ext != ".h" && ext != ".cc")) continue;
    std::ifstream in(entry.path());
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      std::smatch match;
      if (std::regex_search(line, match, pattern)) {
        hits.push_back({fs::relative(entry.path(), WAAM_SOURCE_DIR).string() + ":" + std::to_string(number) + ": " +
                            line,
                        match[1].str()});
      }
    }
  }
  return hits;
}

TEST(SourceRules, NoModuleUsesAnotherModulesInternalNamespace) {
  const std::regex pattern(R"(\b(models|planner|twin|analysis)::internal\b)");
  std::vector<std::string> offences;
  for (const std::string& module : kModules) {
    for (const Hit& hit : Grep(module, pattern)) {
      if (hit.group != module) offences.push_back(hit.where);
    }
  }
  EXPECT_THAT(offences, ::testing::IsEmpty())
      << "a module's `internal` namespace is for that module only: make what others need public";
}

TEST(SourceRules, NoFileIncludesAHigherLayer) {
  const std::regex pattern(R"re(^\s*#\s*include\s+"(models|planner|twin|analysis|app)/)re");
  std::vector<std::string> offences;
  for (const std::string& module : kModules) {
    for (const Hit& hit : Grep(module, pattern)) {
      if (LayerOf(hit.group) > LayerOf(module)) offences.push_back(hit.where);
    }
  }
  EXPECT_THAT(offences, ::testing::IsEmpty()) << "layers are models <- planner <- twin <- analysis <- app";
}

// The code of a line: what precedes a `//` comment (a `//` inside "file://" or "package://" is not one).
std::string CodeOf(const std::string& line) {
  for (std::size_t at = line.find("//"); at != std::string::npos; at = line.find("//", at + 2)) {
    if (at == 0 || line[at - 1] == ' ' || line[at - 1] == '\t') return line.substr(0, at);
  }
  return line;
}

// What reads or writes a file: a stream or C file opened (or <fstream> included), a whole file read or written
// (atomically or not), an XML, YAML, model or parameter file loaded, a folder listed or changed, a file's size, time
// or existence asked (fs::exists, is_directory, ...: the loader checks the paths a scenario names); MuJoCo loading
// from the disk (mj_loadXML without a VFS, mj_addFileVFS, mj_loadModel) or saving.
const std::regex kFileAccess(
    R"re(::Load\(|(^|\W)(std::ifstream|std::ofstream|std::fstream|#\s*include\s*<fstream>|fopen|freopen|)re"
    R"re(ReadFile\(|WriteFileAtomic|AtomicOutput|LoadFile\(|SaveFile\(|LoadYamlFile|YAML::LoadFile|)re"
    R"re(LoadVoidLengthModel|ReadModelJson|ReadDistortionParams|DefaultModelPath|directory_iterator|file_size|)re"
    R"re(last_write_time|create_director(y|ies)|remove_all|copy_file|mj_loadXML\([^,]*,\s*(nullptr|NULL|0)\s*,|)re"
    R"re((fs|filesystem)::(exists|is_directory|is_regular_file|is_symlink|status|symlink_status|canonical)\(|)re"
    R"re(mj_addFileVFS|mj_loadModel|mj_saveLastXML|mj_saveModel))re");

// Every line of `module` whose code (comments left out) reads or writes a file.
std::vector<std::string> FileAccesses(const std::string& module) {
  std::vector<std::string> offences;
  for (const Hit& hit : Grep(module, std::regex(".*"))) {
    const std::size_t text = hit.where.find(": ");
    if (std::regex_search(CodeOf(hit.where.substr(text + 2)), kFileAccess)) offences.push_back(hit.where);
  }
  return offences;
}

TEST(SourceRules, PlannerReadsNoFile) {
  EXPECT_THAT(FileAccesses("planner"), ::testing::IsEmpty())
      << "the planner computes on data: read or write the file in analysis/ (or the scenario loader) and hand over "
         "its bytes or what was parsed from it";
}

TEST(SourceRules, TwinReadsNoFile) {
  EXPECT_THAT(FileAccesses("twin"), ::testing::IsEmpty())
      << "the twin computes on data: read or write the file in analysis/ (analysis/cell_files.h reads the cell's "
         "MJCF, URDF and meshes; MuJoCo gets them in a VFS) and hand over its bytes or what was parsed from it";
}

TEST(SourceRules, TheFileAccessPatternMatchesAReadOrWriteAndSkipsACommentAndAVfsLoad) {
  for (const std::string line :
       {"  std::ifstream in(path);", "  const std::string text = ReadFile(path);",
        "  auto m = models::CswModel::Load(p);", "  YAML::Node n = LoadYamlFile(f);", "#include <fstream>",
        "  std::ofstream(p) << text;", "  WriteFileAtomic(path, out);", "  AtomicOutput output(path);",
        "  FILE* f = fopen(name, \"rb\");", "  doc_.LoadFile(file_.c_str());",
        "  const auto size = fs::file_size(file, ec);", "  fs::create_directories(dir);",
        "  WAAM_THROW_UNLESS(fs::exists(path, ec), where);", "  if (std::filesystem::is_directory(dir)) return;",
        "  m = mj_loadXML(file.string().c_str(), nullptr, error, sizeof(error));",
        "  mj_addFileVFS(vfs, dir, name);", "  f = uri.rfind(\"file://\", 0); std::ifstream in(f);"}) {
    EXPECT_TRUE(std::regex_search(CodeOf(line), kFileAccess)) << line;
  }
  for (const std::string line :
       {"  // the loader calls ReadFile(path) for us", "  m = mj_loadXML(vfs.main().c_str(), vfs.get(), error, 1024);",
        "  x = 1;  // not std::ifstream here", "  const bool file = uri.rfind(\"file://\", 0) == 0;",
        "  spec.mesh_path = fs::absolute(path, ec).lexically_normal();", "  const bool exists = true;"}) {
    EXPECT_FALSE(std::regex_search(CodeOf(line), kFileAccess)) << line;
  }
}

// The check itself finds what it looks for (a rule that cannot fail is no rule).
TEST(SourceRules, TheInternalPatternMatchesAQualifiedUse) {
  const std::regex pattern(R"(\b(models|planner|twin|analysis)::internal\b)");
  std::smatch match;
  const std::string line = "  planner::internal::YamlMap top;";
  ASSERT_TRUE(std::regex_search(line, match, pattern));
  EXPECT_EQ(match[1].str(), "planner");
}

}  // namespace
}  // namespace waam
