// libFuzzer target: the URDF arm parser (links, joints, limits, collision geometry, the meshes it names). Any input
// may be refused with waam::InputError; anything else (a crash, a sanitizer report, another exception, a hang) is a
// bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_input.h"
#include "models/core/error.h"
#include "twin/cell/urdf_arm.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)waam::twin::ParseUrdfArm(text, "input.urdf", {});
  } catch (const waam::InputError& e) {
    waam::fuzz::CheckOneLine(e);
  }
  return 0;
}
