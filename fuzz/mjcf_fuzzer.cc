// libFuzzer target: the cell MJCF reader (analysis::ReadMjcf: the model's text and every file it names). Any input
// may be refused with waam::InputError; anything else (a crash, a sanitizer report, another exception, a hang) is a
// bug.
#include <cstddef>
#include <cstdint>

#include "analysis/cell_files.h"
#include "fuzz/fuzz_input.h"
#include "models/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)waam::analysis::ReadMjcf(waam::fuzz::WriteScratchFile("cell.xml", data, size));
  } catch (const waam::InputError& e) {
    waam::fuzz::CheckOneLine(e);
  }
  return 0;
}
