// Scope guard for HDF5 C API handles (internal to the analysis module's .cc files; exposes hdf5.h).
#pragma once

#include <hdf5.h>

namespace waam::analysis::internal {

// Closes an HDF5 handle (file, group, dataset, dataspace, attribute, type) when it goes out of scope.
class H5Handle {
 public:
  H5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~H5Handle() {
    if (id_ >= 0) close_(id_);
  }
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  hid_t get() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

}  // namespace waam::analysis::internal
