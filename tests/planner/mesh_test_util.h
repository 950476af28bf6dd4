// Helpers for the mesh tests: a fresh temporary folder per test, raw file writing, and an STL file read and parsed.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "models/core/files.h"
#include "planner/mesh/stl_io.h"

namespace waam::planner::testing {

// The STL file `path` read and parsed as analysis::ReadStl does (the planner's parser on the file's bytes).
inline TriangleMesh ReadStl(const std::filesystem::path& path, double weld_tolerance_mm, MeshReport* report) {
  return ParseStl(ReadFile(path), path, weld_tolerance_mm, report);
}

// A folder unique to the running test, emptied on creation.
inline std::filesystem::path TestDir() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::path(::waam_test_env::TempDir()) / "waam_mesh_tests" /
                                    (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Writes `bytes` to `path` as they are.
inline void WriteBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace waam::planner::testing
