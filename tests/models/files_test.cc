// Tests of atomic output and checked reading.
#include "models/core/files.h"

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"

namespace waam {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path TempDir() {
  fs::path dir = fs::path(::waam_test_env::TempDir()) / "waam_files_test";
  fs::create_directories(dir);
  return dir;
}

TEST(AtomicOutputTest, UncommittedOutputLeavesNothing) {
  const fs::path target = TempDir() / "uncommitted.txt";
  fs::remove(target);
  {
    AtomicOutput out(target);
    std::ofstream(out.temp_path()) << "partial";
  }
  EXPECT_FALSE(fs::exists(target)) << "an output that was never committed must not appear";
  for (const auto& entry : fs::directory_iterator(target.parent_path())) {
    EXPECT_THAT(entry.path().filename().string(), ::testing::Not(HasSubstr("uncommitted.txt.tmp")));
  }
}

TEST(AtomicOutputTest, WriteFileAtomicReplacesContents) {
  const fs::path target = TempDir() / "atomic.txt";
  WriteFileAtomic(target, "first");
  WriteFileAtomic(target, "second");
  EXPECT_EQ(ReadFile(target), "second");
}

TEST(ReadFileTest, MissingFileAndDirectoryAreNamed) {
  try {
    ReadFile("/nonexistent/waam/file.stl");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/waam/file.stl: file not found"));
  }
  try {
    ReadFile(TempDir());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("is a directory"));
  }
}

}  // namespace
}  // namespace waam
