// Tests of the output-folder lock: a second process is refused, a killed holder does not block.
#include "models/core/output_lock.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"

namespace waam {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("waam_lock_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  return dir;
}

// Forks a child that claims `dir`, reports on a pipe and waits to be killed. Returns the child's pid.
pid_t StartHolder(const fs::path& dir) {
  int ready[2];
  EXPECT_EQ(::pipe(ready), 0);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(ready[0]);
    char status = '1';
    try {
      ClaimOutputDirectory(dir);
    } catch (...) {
      status = '0';
    }
    if (::write(ready[1], &status, 1) != 1) ::_exit(3);
    for (;;) ::pause();
  }
  ::close(ready[1]);
  char status = '0';
  EXPECT_EQ(::read(ready[0], &status, 1), 1);
  ::close(ready[0]);
  EXPECT_EQ(status, '1') << "the child could not claim a free folder";
  return pid;
}

void Kill9(pid_t pid) {
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
}

TEST(OutputLockTest, SecondProcessIsRefusedAndKilledHolderDoesNotBlock) {
  const fs::path dir = FreshDir("busy");
  const pid_t holder = StartHolder(dir);
  try {
    ClaimOutputDirectory(dir);
    ADD_FAILURE() << "a folder held by pid " << holder << " must be refused";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(dir.string()));
    EXPECT_THAT(e.what(), HasSubstr("in use by pid " + std::to_string(holder)));
  }
  Kill9(holder);
  EXPECT_TRUE(fs::exists(dir / kOutputLockName)) << "kill -9 leaves the lock file behind";
  EXPECT_NO_THROW(ClaimOutputDirectory(dir)) << "a lock left by a killed process must not block";
}

TEST(OutputLockTest, ClaimingTwiceInOneProcessIsAllowed) {
  const fs::path dir = FreshDir("twice");
  ClaimOutputDirectory(dir);
  EXPECT_NO_THROW(ClaimOutputDirectory(dir));
  EXPECT_NO_THROW(ClaimOutputDirectory(dir / "sub")) << "a sub-folder is a folder of its own";
}

TEST(OutputLockTest, HolderExitingNormallyRemovesItsLockFile) {
  const fs::path dir = FreshDir("clean");
  const pid_t pid = ::fork();
  if (pid == 0) {
    ClaimOutputDirectory(dir);
    std::exit(0);  // runs static destructors, as the CLI's return from main does
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_TRUE(fs::is_directory(dir));
  EXPECT_FALSE(fs::exists(dir / kOutputLockName)) << "a normal exit leaves no lock file";
}

}  // namespace
}  // namespace waam
