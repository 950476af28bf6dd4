// One input of the process-log fuzz target (fuzz/replay_log_fuzzer.cc), shared with the regression test that replays
// the kept inputs (tests/analysis/fuzz_regressions_test.cc): the first byte picks the time unit, delimiter and header
// rows, the rest is the log, read by analysis/replay_log.h.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "analysis/replay_log.h"

namespace waam::fuzz {

// The section the first byte `mode` describes: its time unit, delimiter and header rows, power from `power_w`, one
// thermocouple `T1`.
inline analysis::ReplaySection ReplayLogFuzzSection(std::uint8_t mode) {
  analysis::ReplaySection section;
  section.time_unit = static_cast<analysis::LogTimeUnit>(mode % 3);
  section.delimiter = static_cast<analysis::LogDelimiter>((mode / 3) % 4);
  section.header_rows = (mode / 12) % 3;
  section.columns.power_w = "power_w";
  section.probes.push_back({"tc", "T1", Eigen::Vector3d::Zero(), "replay.probes.tc"});
  return section;
}

// Reads `size` bytes (at least 1) as the target does; throws InputError as the reader does. Returns false when an
// accepted log breaks the reader's promises: rows in strictly increasing time, finite times and heads, power >= 0.
inline bool ReplayLogFuzzOne(const std::uint8_t* data, std::size_t size) {
  const analysis::ReplaySection section = ReplayLogFuzzSection(data[0]);
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  const analysis::ReplayLog log = analysis::ParseReplayLog(text, section, "fuzz.csv");
  for (std::size_t i = 0; i < log.time_s.size(); ++i) {
    if (!std::isfinite(log.time_s[i]) || !(log.power_w[i] >= 0.0) || !std::isfinite(log.power_w[i]) ||
        !log.head_mm[i].allFinite()) {
      return false;
    }
    if (i > 0 && !(log.time_s[i] > log.time_s[i - 1])) return false;
  }
  return true;
}

}  // namespace waam::fuzz
