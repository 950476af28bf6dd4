// An output folder belongs to one command at a time: an advisory flock on <folder>/.waam.lock.
#pragma once

#include <filesystem>

namespace waam {

// The name of the lock file a command holds in its output folder while it runs.
inline constexpr const char* kOutputLockName = ".waam.lock";

// Creates `dir` like EnsureOutputDirectory and claims it for this process until the process ends: takes an
// advisory flock on `dir`/.waam.lock and writes this process's pid and command line into it. Claiming a folder
// this process already holds does nothing. A lock left by a killed process does not block (the kernel drops a
// dead process's flock). The lock file is removed when the process exits normally.
// Throws InputError, one line naming the folder and the holding pid, if another process holds the folder, and
// InputError if the folder or its lock file cannot be created.
void ClaimOutputDirectory(const std::filesystem::path& dir);

}  // namespace waam
