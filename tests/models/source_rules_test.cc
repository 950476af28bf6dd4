// The house's rules on the sources themselves: no module names another module's `internal` namespace, no file
// includes a header of a layer above its own (models <- planner <- twin <- analysis <- app), and the planner reads no
// file (readers are called from analysis/).
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

// What reads a file: a stream or C file opened, a whole file read, a YAML, model or parameter file loaded, a folder
// listed. Comments are not code.
const std::regex kFileRead(
    R"re(^[^/]*?\b(std::ifstream|std::fstream|fopen|ReadFile\(|LoadYamlFile|YAML::LoadFile|Model::Load\(|::Load\(|LoadVoidLengthModel|ReadModelJson|ReadDistortionParams|DefaultModelPath|directory_iterator))re");

// The modules that compute on data handed to them and never read a file.
const std::vector<std::string> kReadNoFile = {"planner"};

TEST(SourceRules, PlannerReadsNoFile) {
  std::vector<std::string> offences;
  for (const std::string& module : kReadNoFile) {
    for (const Hit& hit : Grep(module, kFileRead)) offences.push_back(hit.where);
  }
  EXPECT_THAT(offences, ::testing::IsEmpty())
      << "the planner computes on data: read the file in analysis/ (or the scenario loader) and hand over its "
         "bytes or what was parsed from it";
}

TEST(SourceRules, TheFileReadPatternMatchesAReadAndSkipsAComment) {
  for (const std::string line : {"  std::ifstream in(path);", "  const std::string text = ReadFile(path);",
                                 "  auto m = models::CswModel::Load(p);", "  YAML::Node n = LoadYamlFile(f);"}) {
    EXPECT_TRUE(std::regex_search(line, kFileRead)) << line;
  }
  EXPECT_FALSE(std::regex_search(std::string("  // the loader calls ReadFile(path) for us"), kFileRead));
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
