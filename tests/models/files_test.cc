// Tests of atomic output and checked reading.
#include "models/core/files.h"

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/core/json_text.h"

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

// A user's Latin-1 text (a KRL comment, a controller's program name) reaches JSON outputs: JsonText writes U+FFFD for
// each byte sequence that is not UTF-8 instead of throwing, and leaves UTF-8 as it is.
TEST(JsonTextTest, TextThatIsNotUtf8IsReplacedNotRefused) {
  const nlohmann::json latin1 = {{"name", std::string("Schwei\xdf" "naht")}};
  EXPECT_THROW((void)latin1.dump(), nlohmann::json::type_error);
  EXPECT_EQ(JsonText(latin1, -1), "{\"name\":\"Schwei\xef\xbf\xbdnaht\"}");
  const nlohmann::json utf8 = {{"name", "Schwei\xc3\x9fnaht"}};
  EXPECT_EQ(JsonText(utf8, -1), "{\"name\":\"Schwei\xc3\x9fnaht\"}");
  EXPECT_EQ(JsonText(utf8), "{\n  \"name\": \"Schwei\xc3\x9fnaht\"\n}");
}

}  // namespace
}  // namespace waam
