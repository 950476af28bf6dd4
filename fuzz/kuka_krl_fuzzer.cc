// libFuzzer target: the KUKA KRL (a .src followed by its .dat) reader, then the conversion of what it read into a plan (fuzz/program_fuzz.h).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz/fuzz_input.h"
#include "fuzz/program_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    waam::fuzz::ReadAndPlanProgram(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.src",
                                   waam::planner::ProgramFormat::kKukaKrl);
  } catch (const waam::InputError& e) {
    waam::fuzz::CheckOneLine(e);
  }
  return 0;
}
