// Ctrl-C on long runs: `waam simulate` and `waam plan` get SIGINT while working and must exit with code 130,
// say so on stderr, and leave no summary JSON and no partial output behind.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using cli_test::TempDir;
using cli_test::Slurp;
using cli_test::FilesUnder;

struct Interrupted {
  bool signalled = false;  // the marker appeared and SIGINT was sent while the run was still going
  int exit_code = -1;
  std::string err;
};

// Starts `waam <args>` with stderr to `err_file`, waits (up to 10 min) until stderr shows `marker` (the label of a
// progress bar: the run is inside that phase), sends SIGINT and waits for the exit.
Interrupted RunAndInterrupt(const std::vector<std::string>& args, const std::string& marker, const fs::path& err_file) {
  Interrupted result;
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 2);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    std::vector<char*> argv;
    std::string binary = WAAM_BINARY;
    argv.push_back(binary.data());
    std::vector<std::string> copy = args;
    for (std::string& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(binary.c_str(), argv.data());
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(pid, &status, WNOHANG) == pid) {  // finished before the marker: nothing was interrupted
      result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      result.err = Slurp(err_file);
      return result;
    }
    if (Slurp(err_file).find(marker) != std::string::npos) {
      result.signalled = ::kill(pid, SIGINT) == 0;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::waitpid(pid, &status, 0);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.err = Slurp(err_file);
  return result;
}

const std::string kLargeBlock = std::string(WAAM_SOURCE_DIR) + "/scenarios/twin/large_block.yaml";

TEST(InterruptTest, SimulateStopsDuringDepositionWithCode130AndNoOutputs) {
  const fs::path dir = TempDir("simulate");
  // The largest scenario at 1 mm voxels: long enough to be caught depositing, small enough for the sanitizer run.
  const Interrupted run = RunAndInterrupt(
      {"simulate", kLargeBlock, "-o", (dir / "out").string(), "--set", "simulation.voxel_mm=1.0", "--no-images"},
      "deposit", dir / "stderr.txt");
  ASSERT_TRUE(run.signalled) << "the run ended (code " << run.exit_code << ") before it began depositing: "
                             << run.err;
  EXPECT_EQ(run.exit_code, 130) << run.err;
  EXPECT_THAT(run.err, HasSubstr("waam: interrupted; partial outputs were removed"));
  EXPECT_FALSE(fs::exists(dir / "out" / "simulate.json")) << "an interrupted run must not leave its summary";
  EXPECT_THAT(FilesUnder(dir / "out"), ::testing::IsEmpty()) << "no partial output (nor temporary file) may remain";
}

TEST(InterruptTest, PlanStopsWhilePlanningAndKeepsNoStaleSummary) {
  const fs::path dir = TempDir("plan");
  fs::create_directories(dir / "out");
  // A summary from an earlier run in the same folder: the interrupted run must not let it pass for its own.
  std::ofstream(dir / "out" / "plan.json") << "{\"stale\": true}\n";
  const Interrupted run = RunAndInterrupt({"plan", kLargeBlock, "-o", (dir / "out").string()}, "pictures",
                                          dir / "stderr.txt");
  ASSERT_TRUE(run.signalled) << "the run ended (code " << run.exit_code << ") before drawing the layers: " << run.err;
  EXPECT_EQ(run.exit_code, 130) << run.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "plan.json")) << "the stale summary must be gone";
  EXPECT_THAT(FilesUnder(dir / "out"), ::testing::IsEmpty()) << "plan.h5 and the layer pictures drawn so far go too";
}

}  // namespace
}  // namespace waam::analysis
