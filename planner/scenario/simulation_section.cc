// The scenario's optional `simulation` section: settings of the voxel deposition twin, each key checked and ranged.
#include "planner/scenario/simulation_settings.h"
#include "planner/scenario/yaml_fields.h"

#include <system_error>

#include "models/core/error.h"

namespace waam::planner::internal {

void ParseSimulationSection(YamlMap& top, SimulationSettings* out, const std::filesystem::path& base_dir) {
  if (!top.Has("simulation")) return;
  YamlMap sim = top.Map("simulation");
  SimulationSettings& s = *out;
  s.voxel_mm = sim.Number("voxel_mm", 0.1, 2.0, s.voxel_mm);
  s.max_voxels = static_cast<std::size_t>(sim.Number("max_voxels", 1000.0, 2.0e9, static_cast<double>(s.max_voxels)));
  s.blend = sim.Enum("blend", s.blend);
  s.blend_radius_mm = sim.Number("blend_radius_mm", 0.0, 100.0, s.blend_radius_mm);
  s.blend_time_s = sim.Number("blend_time_s", 0.0, 10.0, s.blend_time_s);
  s.start_length_mm = sim.Number("start_length_mm", 0.0, 200.0, s.start_length_mm);
  s.start_height_factor = sim.Number("start_height_factor", 0.2, 3.0, s.start_height_factor);
  s.start_width_factor = sim.Number("start_width_factor", 0.2, 3.0, s.start_width_factor);
  s.stop_length_mm = sim.Number("stop_length_mm", 0.0, 200.0, s.stop_length_mm);
  s.stop_height_factor = sim.Number("stop_height_factor", 0.2, 3.0, s.stop_height_factor);
  s.stop_width_factor = sim.Number("stop_width_factor", 0.2, 3.0, s.stop_width_factor);
  s.stop_crater = sim.Enum("stop_crater", s.stop_crater);
  s.start_wetting = sim.Enum("start_wetting", s.start_wetting);
  s.edge_sag_factor = sim.Number("edge_sag_factor", 0.0, 10.0, s.edge_sag_factor);
  s.edge_spread_factor = sim.Number("edge_spread_factor", 0.0, 1.0, s.edge_spread_factor);
  s.step_mm = sim.Number("step_mm", 0.0, 10.0, s.step_mm);
  s.min_void_volume_mm3 = sim.Number("min_void_volume_mm3", 0.0, 1.0e6, s.min_void_volume_mm3);
  s.curvature_width = sim.Enum("curvature_width", s.curvature_width);
  s.csw_min_radius_mm = sim.Number("csw_min_radius_mm", 1.0, 10000.0, s.csw_min_radius_mm);
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

}  // namespace waam::planner::internal
