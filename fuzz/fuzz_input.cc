// Scratch files for the fuzz targets (the STL reader and the scenario loader read from a path) and the one-line check.
#include "fuzz/fuzz_input.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include <unistd.h>

namespace waam::fuzz {
namespace fs = std::filesystem;

namespace {

// <tmp>/waam_fuzz_<pid>/root/sub: files are written in sub; root/meshes and root/sub/meshes link to the
// repository's meshes ("meshes/x.stl" and "../meshes/x.stl" both resolve, as in scenarios/ and scenarios/twin/).
fs::path ScratchFolder() {
  static const fs::path folder = [] {
    const char* tmp = std::getenv("TMPDIR");
    const fs::path root = fs::path(tmp && *tmp ? tmp : "/tmp") / ("waam_fuzz_" + std::to_string(getpid())) / "root";
    const fs::path sub = root / "sub";
    const fs::path meshes = fs::path(WAAM_SOURCE_DIR) / "scenarios" / "meshes";
    std::error_code ec;
    fs::create_directories(sub, ec);
    fs::create_directory_symlink(meshes, root / "meshes", ec);
    fs::create_directory_symlink(meshes, sub / "meshes", ec);
    return sub;
  }();
  return folder;
}

}  // namespace

fs::path WriteScratchFile(const char* name, const std::uint8_t* data, std::size_t size) {
  const fs::path path = ScratchFolder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (out.fail()) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

void CheckOneLine(const waam::InputError& error) {
  for (const char* c = error.what(); *c != '\0'; ++c) {
    const auto byte = static_cast<unsigned char>(*c);
    if (byte < 0x20 || byte == 0x7f) {
      std::fprintf(stderr, "fuzz: the InputError message holds the control byte 0x%02x: %s\n", byte, error.what());
      std::abort();
    }
  }
}

}  // namespace waam::fuzz
