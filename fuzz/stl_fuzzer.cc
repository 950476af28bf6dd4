// libFuzzer target: the STL parser (binary and ASCII), the mesh report and the sliceability check.
// Any input may be refused with waam::InputError; anything else (a crash, a sanitizer report, another exception,
// a hang) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_input.h"
#include "models/core/error.h"
#include "planner/mesh/stl_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  // The weld tolerance comes from the first byte when there is one, so both exact and tolerant welding are tried.
  const double weld_tolerance_mm = size > 0 ? (data[0] % 4) * 0.01 : 0.0;
  try {
    waam::planner::MeshReport report;
    waam::planner::ParseStl(bytes, "input.stl", weld_tolerance_mm, &report);
    (void)waam::planner::MeshReportJson(report);
    waam::planner::CheckSliceable(report);
  } catch (const waam::InputError& e) {
    waam::fuzz::CheckOneLine(e);
  }
  return 0;
}
