// Atomic file output and checked file reading.
#include "models/core/files.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
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
  if (!fs::exists(temp_path_, ec)) ThrowOutputError(final_path_, "nothing was written");
  fs::rename(temp_path_, final_path_, ec);
  if (ec) ThrowOutputError(final_path_, ec.message());
  committed_ = true;
}

void WriteFileAtomic(const fs::path& path, std::string_view contents) {
  AtomicOutput out(path);
  {
    errno = 0;
    std::ofstream stream(out.temp_path(), std::ios::binary | std::ios::trunc);
    if (!stream) ThrowOutputError(path, LastSystemError("cannot open for writing"));
    stream.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    stream.flush();
    if (!stream) ThrowOutputError(path, LastSystemError("write failed"));
    stream.close();
    if (stream.fail()) ThrowOutputError(path, LastSystemError("close failed"));
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
    if (!fs::is_directory(dir, ec)) ThrowOutputError(dir, "exists and is not a directory");
    return;
  }
  fs::create_directories(dir, ec);
  if (ec) ThrowOutputError(dir, "cannot create the directory: " + ec.message());
}

void ThrowOutputError(const fs::path& path, const std::string& reason) {
  throw OutputError("cannot write " + path.string() + ": " + reason);
}

std::string LastSystemError(const std::string& fallback) {
  const int error = errno;
  return error == 0 ? fallback : std::string(std::strerror(error));
}

}  // namespace waam
