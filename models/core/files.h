// Atomic file output: results appear complete under their final name or not at all.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace waam {

// A temporary file next to `final_path` that becomes `final_path` only on Commit(). If the object is destroyed
// without Commit() (an exception, an interrupt), the temporary is removed and `final_path` is untouched.
// Writers that need a file name (HDF5) write to temp_path().
class AtomicOutput {
 public:
  // Creates the parent directory of `final_path` if needed. Throws OutputError if it cannot be created.
  explicit AtomicOutput(std::filesystem::path final_path);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  const std::filesystem::path& temp_path() const { return temp_path_; }
  const std::filesystem::path& final_path() const { return final_path_; }

  // Renames the temporary onto the final name. Throws OutputError if the temporary is missing or the rename fails
  // (e.g. `final_path` is a directory).
  void Commit();

 private:
  std::filesystem::path final_path_;
  std::filesystem::path temp_path_;
  bool committed_ = false;
};

// Writes `contents` to `path` atomically (temporary file, flush, close, rename). Throws OutputError naming the path
// and the system's reason when any of these fails (disk full, no permission, a parent that is a file).
void WriteFileAtomic(const std::filesystem::path& path, std::string_view contents);

// Reads a whole file. Throws InputError naming the file if it is missing, a directory or unreadable.
std::string ReadFile(const std::filesystem::path& path);

// Creates `dir` (and parents) for outputs. Throws OutputError if it exists as a file or cannot be created.
void EnsureOutputDirectory(const std::filesystem::path& dir);

// Throws OutputError "cannot write <path>: <reason>". Writers of other formats (HDF5, STL) call it when a write fails.
[[noreturn]] void ThrowOutputError(const std::filesystem::path& path, const std::string& reason);

// The system's reason for the last failed call (strerror(errno)), or `fallback` when errno is 0.
std::string LastSystemError(const std::string& fallback);

}  // namespace waam
