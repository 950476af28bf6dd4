// Shared helpers of the models tests: temporary directories and paths of the project data.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace waam::testing {

// A fresh directory under the system temp dir, unique per test.
inline std::filesystem::path TestDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = std::filesystem::path(::waam_test_env::TempDir()) /
                              ("waam_models_" + std::string(info->test_suite_name()) + "_" + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Writes `text` to `dir/name` and returns the path.
inline std::filesystem::path WriteText(const std::filesystem::path& dir, const std::string& name,
                                       const std::string& text) {
  const std::filesystem::path path = dir / name;
  std::ofstream(path) << text;
  return path;
}

inline std::filesystem::path ModelsData(const std::string& name) {
  return std::filesystem::path(WAAM_SOURCE_DIR) / "models" / "data" / name;
}

}  // namespace waam::testing
