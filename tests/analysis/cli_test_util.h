// Helpers shared by the analysis tests that run the `waam` executable and read what it writes.
#pragma once

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <functional>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "models/core/files.h"

namespace waam::analysis::cli_test {

// A 30 x 20 x 3 mm block, two layers, 1 mm voxels: a whole `waam run` takes well under a second of compute.
inline constexpr char kTinyBlockScenario[] = R"(name: tiny_block
part:
  generator: {type: box, size_mm: [30, 20, 3]}
slicing:
  type: planar
  layer_height_mm: 1.5
path:
  pattern: continuous
  bead_width_mm: 6
process:
  travel_speed_mm_min: 400
  wire_feed_mm_min: 3200
simulation:
  voxel_mm: 1.0
)";

// An empty folder for one test: <tmp>/waam_analysis_test_<pid>/<name> (per process, since ctest runs tests in
// parallel processes).
inline std::filesystem::path TempDir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("waam_analysis_test_" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The whole file, or "" when it cannot be read.
inline std::string Slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline nlohmann::json ReadJson(const std::filesystem::path& path) { return nlohmann::json::parse(ReadFile(path)); }

// Runs the built executable with `args` (stdout discarded), returns its exit code (-1 if it did not exit) and its
// stderr in `*err`.
inline int RunWaam(const std::string& args, std::string* err) {
  const std::filesystem::path err_file = TempDir("run_waam") / "stderr.txt";
  const std::string command = std::string(WAAM_BINARY) + " " + args + " >/dev/null 2>" + err_file.string();
  const int status = std::system(command.c_str());
  *err = Slurp(err_file);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The output directory of `waam <args> -o <dir>`, run once for every test process of this build that asks for the
// same args (ctest runs each test in a process of its own): the first to get here runs it under an exclusive lock
// of the directory, the others wait for the lock and reuse its output. The directory is keyed by the args and the
// executable's size and modification time, so a rebuilt executable runs again. A failed run leaves no "done" mark
// and fails the test that made it (and each test after it that runs it again).
inline std::filesystem::path SharedRun(const std::string& args) {
  struct stat binary {};
  EXPECT_EQ(::stat(WAAM_BINARY, &binary), 0) << WAAM_BINARY;
  const std::string key = args + "|" + std::to_string(binary.st_size) + "|" +
                          std::to_string(binary.st_mtim.tv_sec) + "." + std::to_string(binary.st_mtim.tv_nsec);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("waam_shared_run_" + std::to_string(std::hash<std::string>{}(key)));
  std::filesystem::create_directories(dir);
  const int lock = ::open((dir / "lock").c_str(), O_CREAT | O_RDWR, 0644);
  EXPECT_GE(lock, 0) << dir;
  ::flock(lock, LOCK_EX);
  const std::filesystem::path out = dir / "out";
  if (!std::filesystem::exists(dir / "done")) {
    std::filesystem::remove_all(out);
    std::string err;
    const int code = RunWaam(args + " -o " + out.string(), &err);
    EXPECT_EQ(code, 0) << err;
    if (code == 0) std::ofstream(dir / "done") << key << "\n";
  }
  ::flock(lock, LOCK_UN);
  ::close(lock);
  return out;
}

// Every file below `dir` (none when it does not exist).
inline std::vector<std::string> FilesUnder(const std::filesystem::path& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  if (!std::filesystem::exists(dir, ec)) return files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (!entry.is_directory()) files.push_back(entry.path().string());
  }
  return files;
}

}  // namespace waam::analysis::cli_test
