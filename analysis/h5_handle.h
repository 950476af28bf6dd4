// Scope guard and error checks for HDF5 C API handles (internal to the analysis module's .cc files; exposes hdf5.h).
#pragma once

#include <hdf5.h>

#include <filesystem>

namespace waam::analysis::internal {

// Closes an HDF5 handle (file, group, dataset, dataspace, attribute, type) when it goes out of scope.
class H5Handle {
 public:
  H5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~H5Handle() {
    if (id_ >= 0) close_(id_);
  }
  H5Handle(H5Handle&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  hid_t get() const { return id_; }

  // Closes now and returns whether the close succeeded: closing a file flushes it, so a full disk shows here.
  bool Close() {
    const herr_t status = id_ >= 0 ? close_(id_) : -1;
    id_ = -1;
    return status >= 0;
  }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// Creates (truncates) the HDF5 file `temp_path` for the output `final_path`, with HDF5's own printing of errors to
// stderr turned off (failures are reported by CheckH5Output). Throws OutputError naming `final_path` and the reason.
H5Handle CreateH5Output(const std::filesystem::path& temp_path, const std::filesystem::path& final_path);

// Throws OutputError "cannot write <final_path>: HDF5 <what> failed: <reason>" unless `ok`; the reason is the
// innermost message on HDF5's error stack (e.g. the system's "No space left on device").
void CheckH5Output(bool ok, const std::filesystem::path& final_path, const char* what);

// Closes `file` (flushing it) and throws OutputError as CheckH5Output does if that fails.
void CloseH5Output(H5Handle* file, const std::filesystem::path& final_path);

}  // namespace waam::analysis::internal
