// The twin's settings: their validation and the scenario's optional `simulation` section, each key checked and
// ranged by the one table of kSimulationNumbers.
#include "twin/simulation_settings.h"

#include <system_error>

#include "models/core/error.h"
#include "planner/scenario/yaml_fields.h"

namespace waam::twin {

void ValidateSimulationSettings(const SimulationSettings& s) {
  for (const SimulationNumber& n : kSimulationNumbers) {
    const double v = s.*n.field;
    WAAM_THROW_UNLESS(v >= n.min && v <= n.max,
                      "simulation." << n.key << " = " << v << ": must be in [" << n.min << ", " << n.max << "]");
  }
  WAAM_THROW_UNLESS(s.max_voxels >= kMaxVoxelsMin && s.max_voxels <= kMaxVoxelsMax,
                    "simulation.max_voxels = " << s.max_voxels << ": must be in [" << kMaxVoxelsMin << ", "
                                               << kMaxVoxelsMax << "]");
}

}  // namespace waam::twin

namespace waam::twin::internal {

void ParseSimulationSection(YamlMap& top, SimulationSettings* out, const std::filesystem::path& base_dir) {
  if (!top.Has("simulation")) return;
  YamlMap sim = top.Map("simulation");
  SimulationSettings& s = *out;
  for (const SimulationNumber& n : kSimulationNumbers) s.*n.field = sim.Number(n.key, n.min, n.max, s.*n.field);
  s.max_voxels = static_cast<std::size_t>(
      sim.Number("max_voxels", kMaxVoxelsMin, kMaxVoxelsMax, static_cast<double>(s.max_voxels)));
  s.blend = sim.Enum("blend", s.blend);
  s.stop_crater = sim.Enum("stop_crater", s.stop_crater);
  s.start_wetting = sim.Enum("start_wetting", s.start_wetting);
  s.curvature_width = sim.Enum("curvature_width", s.curvature_width);
  if (sim.Has("csw_model")) {
    std::filesystem::path file = sim.String("csw_model");
    if (file.is_relative()) file = base_dir / file;
    std::error_code ec;
    WAAM_THROW_UNLESS(std::filesystem::is_regular_file(file, ec),
                      sim.Where("csw_model") << ": model file " << file.string() << " not found");
    s.csw_model = file.lexically_normal();
  }
  sim.CheckNoUnknownKeys();
}

}  // namespace waam::twin::internal
