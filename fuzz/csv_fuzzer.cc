// libFuzzer target: the CSV reader and its typed column access (every column as numbers, with and without
// infinities, and as text). Any input may be refused with waam::InputError; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz/fuzz_input.h"
#include "models/core/csv.h"
#include "models/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const waam::CsvTable table = waam::CsvTable::Parse(text, "fuzz.csv");
    for (const std::string& column : table.header()) {
      (void)table.ColumnIndex(column);
      (void)table.Strings(column);
      try {
        (void)table.Numbers(column);
      } catch (const waam::InputError& e) {
        waam::fuzz::CheckOneLine(e);
      }
      try {
        (void)table.Numbers(column, /*allow_infinity=*/true);
      } catch (const waam::InputError& e) {
        waam::fuzz::CheckOneLine(e);
      }
    }
    for (std::size_t row = 0; row < table.rows(); ++row) (void)table.line(row);
    (void)table.ColumnIndex("no such column");
  } catch (const waam::InputError& e) {
    waam::fuzz::CheckOneLine(e);
  }
  return 0;
}
