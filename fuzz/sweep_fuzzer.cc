// libFuzzer target: the sweep file reader (YAML syntax, grid and list expansion, key paths, metrics). Any input may
// be refused with waam::InputError; anything else (a crash, a sanitizer report, an escaping yaml-cpp exception, a
// hang) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "analysis/sweep.h"
#include "fuzz/fuzz_input.h"
#include "models/core/error.h"
#include "models/core/json_text.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const waam::analysis::Sweep sweep = waam::analysis::ParseSweep(text, "fuzz/sweep.yaml");
    (void)waam::analysis::SweepBenchRuns(sweep);
    (void)waam::JsonText(waam::analysis::SweepJson(sweep));
  } catch (const waam::InputError& e) {
    waam::fuzz::CheckOneLine(e);
  }
  return 0;
}
