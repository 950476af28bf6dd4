// Where the tests find the source tree and the built `waam` executable, and where they write. The paths live in one
// small file that CMake generates in the build tree (tests/CMakeLists.txt), so no other test file's compile depends on
// where the clone sits (a fresh clone in another folder reuses ccache's objects). Included into every test file by
// CMake.
#pragma once

#include <string>

namespace waam_test_env {
extern const char* const kSourceDir;  // the repository root
extern const char* const kBinary;     // the built waam executable

// A folder of this test process's own, "<temp>/waam_test_<pid>/" (with the trailing '/' of ::waam_test_env::TempDir(),
// <temp> being $TEST_TMPDIR or the system's temp folder): created on first use, removed when the process exits.
// Tests write here, never to a shared /tmp/<name>, so that the same test binary run at once from two build trees (two
// worktrees, two CI jobs) does not meet the other's outputs and output locks.
std::string TempDir();
}  // namespace waam_test_env

#define WAAM_SOURCE_DIR (::waam_test_env::kSourceDir)
#define WAAM_BINARY (::waam_test_env::kBinary)
