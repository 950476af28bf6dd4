// The twin's settings: their validation and the scenario's optional `simulation` section, each key checked and
// ranged by the one table of kSimulationFields.
#include "twin/simulation_settings.h"

#include "models/core/error.h"
#include "models/core/yaml_map.h"

namespace waam::twin {

void ValidateSimulationSettings(const SimulationSettings& s) {
  CheckFields<SimulationSettings>(kSimulationFields, s, "simulation");
}

void ParseSimulationSection(YamlMap& top, SimulationSettings* out) {
  if (!top.Has("simulation")) return;
  YamlMap sim = top.Map("simulation");
  ReadFields<SimulationSettings>(sim, kSimulationFields, out);
  sim.CheckNoUnknownKeys();
}

}  // namespace waam::twin
