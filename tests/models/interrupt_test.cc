// Tests of the interrupt handler: the first SIGTERM asks long loops to stop, a second one ends the process.
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/core/progress.h"

namespace waam {
namespace {

// In a child process (the handler is process-wide): the first signal sets the flag and CheckInterrupt throws;
// the second ends the child by the signal's default action, even though nothing checks the flag.
TEST(InterruptTest, FirstSignalAsksToStopSecondEndsTheProcess) {
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    InstallInterruptHandler();
    if (InterruptRequested()) _exit(10);
    std::raise(SIGTERM);
    if (!InterruptRequested()) _exit(11);
    try {
      CheckInterrupt();
      _exit(12);
    } catch (const Interrupted&) {
    }
    std::raise(SIGTERM);
    _exit(13);  // reached only if the second signal was caught too
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "child exited with " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
}

}  // namespace
}  // namespace waam
