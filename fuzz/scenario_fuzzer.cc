// libFuzzer target: the scenario loader (YAML syntax, types, ranges, unknown keys, mesh and model paths).
// Any input may be refused with waam::InputError; anything else (a crash, a sanitizer report, a yaml-cpp
// exception that escapes, a hang) is a bug.
#include <cstddef>
#include <cstdint>

#include "analysis/scenario.h"
#include "fuzz/fuzz_input.h"
#include "models/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = waam::fuzz::WriteScratchFile("scenario.yaml", data, size);
  try {
    (void)waam::analysis::LoadScenario(path);
  } catch (const waam::InputError& e) {
    waam::fuzz::CheckOneLine(e);
  }
  return 0;
}
