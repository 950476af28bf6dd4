// The tests' per-process temp folder (tests/test_env.h).
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include "tests/test_env.h"

namespace waam_test_env {
namespace {

pid_t owner = 0;  // the process that made the folder (a forked child must not remove it)

std::filesystem::path Folder() {
  const char* base = std::getenv("TEST_TMPDIR");
  std::error_code ec;
  const std::filesystem::path root =
      base && *base ? std::filesystem::path(base) : std::filesystem::temp_directory_path(ec);
  return root / ("waam_test_" + std::to_string(::getpid()));
}

void RemoveFolder() {
  if (::getpid() != owner) return;
  std::error_code ec;
  std::filesystem::remove_all(Folder(), ec);
}

}  // namespace

std::string TempDir() {
  const std::filesystem::path dir = Folder();
  if (owner != ::getpid()) {
    owner = ::getpid();
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    std::atexit(RemoveFolder);
  }
  return dir.string() + "/";
}

}  // namespace waam_test_env
