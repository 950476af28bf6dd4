// libFuzzer target: the process-log reader of `waam thermal replay` (analysis/replay_log.h). The first byte picks
// the time unit, delimiter and header rows; the rest is the log (fuzz/replay_log_fuzz.h). Any input may be refused
// with waam::InputError; anything else is a bug, and every accepted log must be in time order with finite values.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz/fuzz_input.h"
#include "fuzz/replay_log_fuzz.h"
#include "models/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  try {
    if (!waam::fuzz::ReplayLogFuzzOne(data, size)) std::abort();
  } catch (const waam::InputError& e) {
    waam::fuzz::CheckOneLine(e);
  }
  return 0;
}
