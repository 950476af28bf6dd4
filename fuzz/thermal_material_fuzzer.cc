// libFuzzer target: the thermal material reader (models/data/materials format) and the interpolation of what it
// accepts. Any input may be refused with waam::InputError; anything else is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "analysis/thermal_material_io.h"
#include "fuzz/fuzz_input.h"
#include "models/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const waam::models::ThermalMaterial m = waam::analysis::ParseThermalMaterial(text, "fuzz.csv", "fuzz");
    // Every accepted table interpolates to finite, positive properties anywhere (beyond its ends too).
    const double lo = m.temperature_c.front() - 100.0, hi = m.temperature_c.back() + 100.0;
    for (int i = 0; i <= 16; ++i) {
      const double t = lo + (hi - lo) * i / 16.0;
      const double c = m.EffectiveHeatCapacity(t);
      if (!(m.Conductivity(t) > 0.0) || !(m.Density(t) > 0.0) || !(m.SpecificHeat(t) > 0.0) || !(c > 0.0)) {
        std::abort();
      }
    }
  } catch (const waam::InputError& e) {
    waam::fuzz::CheckOneLine(e);
  }
  return 0;
}
