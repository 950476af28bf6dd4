// libFuzzer target: the URDF arm reader (links, joints, limits, collision geometry, mesh lookup). Any input may be
// refused with waam::InputError; anything else (a crash, a sanitizer report, another exception, a hang) is a bug.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_input.h"
#include "models/core/error.h"
#include "twin/cell/urdf_arm.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  waam::twin::UrdfArmOptions options;
  options.urdf = waam::fuzz::WriteScratchFile("input.urdf", data, size);
  options.package_paths = {options.urdf.parent_path()};
  try {
    (void)waam::twin::ReadUrdfArm(options);
  } catch (const waam::InputError&) {
  }
  return 0;
}
