// libFuzzer target: the process-log reader of `waam thermal replay` (analysis/replay_log.h). The first byte picks
// the time unit, delimiter and header rows; the rest is the log. Any input may be refused with waam::InputError;
// anything else is a bug, and every accepted log must be in time order with finite values.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "analysis/replay_log.h"
#include "models/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  waam::analysis::ReplaySection section;
  section.time_unit = static_cast<waam::analysis::LogTimeUnit>(data[0] % 3);
  section.delimiter = static_cast<waam::analysis::LogDelimiter>((data[0] / 3) % 4);
  section.header_rows = (data[0] / 12) % 3;
  section.columns.power_w = "power_w";
  section.probes.push_back({"tc", "T1", Eigen::Vector3d::Zero(), "replay.probes.tc"});
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const waam::analysis::ReplayLog log = waam::analysis::ParseReplayLog(text, section, "fuzz.csv");
    for (std::size_t i = 0; i < log.time_s.size(); ++i) {
      if (!std::isfinite(log.time_s[i]) || !(log.power_w[i] >= 0.0) || !log.head_mm[i].allFinite()) std::abort();
      if (i > 0 && !(log.time_s[i] > log.time_s[i - 1])) std::abort();
    }
  } catch (const waam::InputError&) {
  }
  return 0;
}
