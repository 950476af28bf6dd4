// Error checks of HDF5 output: a failed create, write or close becomes an OutputError naming the file and the reason.
#include "analysis/h5_handle.h"

#include <string>

#include "models/core/files.h"

namespace waam::analysis::internal {
namespace {

// HDF5's exit handler closes the files still open; after a write that failed (a full disk) it crashes on the file
// whose close failed (HDF5 1.10). Every output is closed explicitly, so the handler is turned off before any HDF5 call
// (a static initialiser of this file, which every HDF5 writer links).
[[maybe_unused]] const herr_t kNoExitHandler = H5dont_atexit();

// One line from an HDF5 error description: the system's message when it quotes one ("error message = '...'"),
// else the description up to its first line break.
std::string OneLine(const std::string& desc) {
  const std::string key = "error message = '";
  const std::size_t at = desc.find(key);
  if (at != std::string::npos) {
    const std::size_t end = desc.find('\'', at + key.size());
    if (end != std::string::npos) return desc.substr(at + key.size(), end - at - key.size());
  }
  return desc.substr(0, desc.find_first_of("\r\n"));
}

// Keeps the description of the innermost error record (walked upward, the first one seen).
herr_t KeepInnermost(unsigned n, const H5E_error2_t* record, void* data) {
  auto* reason = static_cast<std::string*>(data);
  if (n == 0 && record != nullptr && record->desc != nullptr) *reason = record->desc;
  return 0;
}

}  // namespace

H5Handle CreateH5Output(const std::filesystem::path& temp_path, const std::filesystem::path& final_path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  H5Handle file(H5Fcreate(temp_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  CheckH5Output(file.get() >= 0, final_path, "file create");
  return file;
}

void CheckH5Output(bool ok, const std::filesystem::path& final_path, const char* what) {
  if (ok) return;
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, KeepInnermost, &reason);
  H5Eclear2(H5E_DEFAULT);
  reason = OneLine(reason);
  ThrowOutputError(final_path, std::string("HDF5 ") + what + " failed" + (reason.empty() ? "" : ": " + reason));
}

void CloseH5Output(H5Handle* file, const std::filesystem::path& final_path) {
  CheckH5Output(file->Close(), final_path, "file close");
}

}  // namespace waam::analysis::internal
