// Where the tests find the source tree and the built `waam` executable. The values live in one small file that
// CMake generates in the build tree (tests/CMakeLists.txt), so no other test file's compile depends on where the
// clone sits (a fresh clone in another folder reuses ccache's objects). Included into every test file by CMake.
#pragma once

namespace waam_test_env {
extern const char* const kSourceDir;  // the repository root
extern const char* const kBinary;     // the built waam executable
}  // namespace waam_test_env

#define WAAM_SOURCE_DIR (::waam_test_env::kSourceDir)
#define WAAM_BINARY (::waam_test_env::kBinary)
