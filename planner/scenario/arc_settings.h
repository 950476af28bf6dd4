// The arc's power and the interpass rule of a scenario's `process:` section (keys `process.arc`, `process.interpass`).
#pragma once

#include <array>
#include <limits>
#include <string>

#include "models/core/enum_names.h"
#include "models/core/field_table.h"

namespace waam::planner {

// process.arc: the electrical power of the arc and the share of it that enters the metal.
struct ArcSettings {
  bool given = false;                                       // the scenario has a process.arc mapping
  double power_w = std::numeric_limits<double>::quiet_NaN();  // arc power, W (power_w, or voltage_v x current_a)
  double voltage_v = std::numeric_limits<double>::quiet_NaN();  // V, when given
  double current_a = std::numeric_limits<double>::quiet_NaN();  // A, when given
  // Arc (process) efficiency: heat into the metal over electrical arc energy. Default 0.84, the consumable-electrode
  // (GMAW) arc efficiency measured by DuPont & Marder, Welding Journal 74(12) 406s, 1995; Pepe et al., Sci. Technol.
  // Weld. Join. 16(5) 412, 2011 measured about 0.85 for controlled dip transfer (CMT, STT).
  double efficiency = 0.84;
  std::string where = "process.arc";                        // "file:line: process.arc" for messages
  // Heat into the metal while the arc burns, W.
  double HeatW() const { return efficiency * power_w; }
};

// process.interpass.at: where the interpass temperature is measured.
enum class InterpassAt {
  kNextStart,  // on the metal under the next layer's first arc start
  kTopMax,     // the hottest point of the layer just finished
  kProbe,      // a named probe (thermal.probes)
};
constexpr std::array<EnumName<InterpassAt>, 3> EnumNames(InterpassAt) {
  return {{{InterpassAt::kNextStart, "next_start"}, {InterpassAt::kTopMax, "top_max"}, {InterpassAt::kProbe, "probe"}}};
}
WAAM_ENUM_JSON(InterpassAt)

// process.interpass: the build waits before each layer until the interpass rule holds.
struct InterpassSettings {
  // Before each layer after the first, wait until the temperature at `at` is at most this, degC; NaN = no limit.
  double max_c = std::numeric_limits<double>::quiet_NaN();
  InterpassAt at = InterpassAt::kNextStart;
  std::string probe;                 // the probe's name (thermal.probes) when at = probe
  double min_layer_time_s = 0.0;     // a layer lasts at least this long from its first arc start to the next
                                     // layer's first arc start; the rest is a wait (planner/timeline), s
  std::string where = "process.interpass";        // "file:line: process.interpass"
  std::string max_where = "process.interpass.max_c";  // "file:line: process.interpass.max_c"
  std::string at_where = "process.interpass.at";      // "file:line: process.interpass.at"
  bool HasMax() const { return max_c == max_c; }  // not NaN
};

// The keys of process.arc: power_w, or voltage_v and current_a (one form, read by ParseArcAndInterpass), and the
// efficiency. The ranges are the parser's and ValidateArcAndInterpass's.
inline constexpr std::array kArcFields = {
    NanField<&ArcSettings::power_w>("power_w", "W", 1.0, 1.0e6, "arc power; or voltage_v and current_a"),
    NanField<&ArcSettings::voltage_v>("voltage_v", "V", 1.0, 200.0, "arc voltage (with current_a)"),
    NanField<&ArcSettings::current_a>("current_a", "A", 1.0, 2000.0, "arc current (with voltage_v)"),
    NumField<&ArcSettings::efficiency>("efficiency", "", 0.05, 1.0, "share of the arc power the metal takes"),
};

// The keys of process.interpass; `at` has two forms: a name, or {probe: NAME} (TaggedField).
inline constexpr std::array kInterpassFields = {
    NanField<&InterpassSettings::max_c>("max_c", "degC", -273.15, 3000.0, "the interpass temperature limit; absent: none"),
    TaggedField<&InterpassSettings::at, &InterpassSettings::probe, InterpassAt::kProbe>(
        "at", "thermal.probes", "where max_c is measured; {probe: NAME}: one of thermal.probes"),
    NumField<&InterpassSettings::min_layer_time_s>("min_layer_time_s", "s", 0.0, 86400.0, "each layer lasts at least"),
};

// Reads the optional `arc:` and `interpass:` mappings of the scenario's `process` map. Throws InputError naming file,
// line and key for unknown keys, out-of-range values, an arc without power (neither power_w nor voltage_v and
// current_a) or with both forms, and `at` not one of next_start, top_max, {probe: NAME}.
void ParseArcAndInterpass(YamlMap& process, ArcSettings* arc, InterpassSettings* interpass);

// Checks arc and interpass settings built in code against the keys' ranges (kArcFields, kInterpassFields) and rules:
// a given arc has a power, and at = probe names its probe. Throws InputError "process.arc.KEY = v: must be in [..]".
void ValidateArcAndInterpass(const ArcSettings& arc, const InterpassSettings& interpass);

}  // namespace waam::planner
