// Atomic file output and checked file reading.
#include "models/core/files.h"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <sstream>
#include <system_error>

#include "models/core/error.h"

namespace waam {
namespace fs = std::filesystem;

namespace {
std::atomic<unsigned> g_temp_counter{0};
}  // namespace

AtomicOutput::AtomicOutput(fs::path final_path) : final_path_(std::move(final_path)) {
  if (final_path_.has_parent_path()) EnsureOutputDirectory(final_path_.parent_path());
  temp_path_ = final_path_;
  temp_path_ += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(g_temp_counter++);
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_path_, ec);
  }
}

void AtomicOutput::Commit() {
  std::error_code ec;
  WAAM_THROW_UNLESS(fs::exists(temp_path_, ec), "output " << final_path_.string() << ": nothing was written");
  fs::rename(temp_path_, final_path_, ec);
  WAAM_THROW_UNLESS(!ec, "output " << final_path_.string() << ": cannot rename temporary file: " << ec.message());
  committed_ = true;
}

void WriteFileAtomic(const fs::path& path, std::string_view contents) {
  AtomicOutput out(path);
  {
    std::ofstream stream(out.temp_path(), std::ios::binary | std::ios::trunc);
    WAAM_THROW_UNLESS(stream, "output " << path.string() << ": cannot open for writing");
    stream.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    stream.flush();
    WAAM_THROW_UNLESS(stream, "output " << path.string() << ": write failed (disk full?)");
  }
  out.Commit();
}

std::string ReadFile(const fs::path& path) {
  std::error_code ec;
  WAAM_THROW_UNLESS(fs::exists(path, ec), path.string() << ": file not found");
  WAAM_THROW_UNLESS(!fs::is_directory(path, ec), path.string() << ": is a directory, expected a file");
  std::ifstream stream(path, std::ios::binary);
  WAAM_THROW_UNLESS(stream, path.string() << ": cannot open for reading");
  std::ostringstream buffer;
  buffer << stream.rdbuf();
  return buffer.str();
}

void EnsureOutputDirectory(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    WAAM_THROW_UNLESS(fs::is_directory(dir, ec), "output directory " << dir.string() << " exists and is not a directory");
    return;
  }
  fs::create_directories(dir, ec);
  WAAM_THROW_UNLESS(!ec, "output directory " << dir.string() << ": cannot create: " << ec.message());
}

}  // namespace waam
