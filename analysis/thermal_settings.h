// The scenario's optional `thermal:` section: the metals, the plate, the grid, the losses and the probes of the
// thermal model (`waam thermal`, docs/THERMAL.md "Commands and outputs").
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "models/bead/bead_temperature_model.h"
#include "models/thermal/material.h"
#include "twin/thermal/heat_source.h"

namespace waam {
class YamlMap;
}  // namespace waam
namespace waam::planner {
struct ProcessSettings;
}  // namespace waam::planner

namespace waam::analysis {

// A point where the temperature history is recorded (thermal.probes), in the part frame.
struct ThermalProbe {
  std::string name;
  Eigen::Vector3d p_mm = Eigen::Vector3d::Zero();  // part frame, mm
  std::string where;                               // "file:line: thermal.probes.NAME"
};

// A metal named by the scenario: a material name of the data folder (mild_steel, ti6al4v, ss316l, ...) or a path to
// a material file (relative to the scenario's folder), and its properties once loaded.
struct ThermalMaterialChoice {
  std::string name_or_path;
  std::string where;                 // "file:line: thermal.material" for messages
  models::ThermalMaterial material;  // filled when the scenario is loaded
};

// thermal.shape: the heat shapes the part (docs/compensation.md, "Heat into shape").
struct ThermalShape {
  std::string bead_model_path;  // thermal.shape.bead_model: a bead-temperature model file; empty = planned beads
  std::string bead_model_where; // "file:line: thermal.shape.bead_model"
  std::optional<models::BeadTemperatureModel> bead_model;  // loaded by LoadScenario
  bool distortion = false;      // thermal.shape.distortion: the inherent strains follow the layers' temperatures
  bool Any() const { return !bead_model_path.empty() || distortion; }
};

struct ThermalSection {
  bool given = false;                // the scenario has a thermal: section
  std::string where;                 // "file:line: thermal"
  ThermalMaterialChoice deposit;     // thermal.material: the wire's metal (required)
  ThermalMaterialChoice substrate;   // thermal.substrate.material (default: the deposit's)
  Eigen::Vector3d substrate_size_mm = Eigen::Vector3d::Zero();  // thermal.substrate.size_mm [x, y, z] (required)
  // thermal.substrate.centre_mm: the plate's centre in the part frame; absent = centred under the part, top at z = 0.
  std::optional<Eigen::Vector3d> substrate_centre_mm;
  std::string substrate_where;       // "file:line: thermal.substrate"
  double cell_mm = 2.0;              // thermal.cell_mm: grid spacing near the deposit, mm
  double ambient_c = 20.0;           // thermal.ambient_c: air (and, by default, plate and table) temperature, degC
  double initial_c = 20.0;           // thermal.initial_c: the plate's temperature at the start (default ambient), degC
  double convection_w_m2k = 10.0;    // thermal.convection_w_m2k: h on every exposed face, W/(m^2 K)
  double emissivity = -1.0;          // thermal.emissivity: < 0 = each material's own
  double table_conductance_w_m2k = 0.0;  // thermal.table.conductance_w_m2k: plate-table contact (0 = no table)
  double table_c = 20.0;             // thermal.table.temperature_c (default ambient), degC
  double sample_s = 1.0;             // thermal.sample_s: interval of the probe histories and interpass checks, s
  // thermal.heat_source and thermal.pool.*: the arc's heat source and its pool's semi-axes over the bead's size
  // (twin::ThermalSettings documents each); thermal.liquid_conductivity_factor: k above the liquidus times this.
  twin::HeatSourceShape heat_source = twin::HeatSourceShape::kDoubleEllipsoid;
  double pool_depth_beads = 2.0;
  double pool_front_widths = 0.5;
  double pool_rear_widths = 2.0;
  double liquid_conductivity_factor = 5.0;
  std::vector<ThermalProbe> probes;  // thermal.probes, in file order
  ThermalShape shape;                // thermal.shape
};

}  // namespace waam::analysis

namespace waam::analysis::internal {
using ::waam::YamlMap;
// Reads the optional `thermal:` mapping of the scenario's top level into `out` (materials by name only; they are
// loaded by LoadScenario). Throws InputError naming file:line and key for unknown keys, out-of-range values, a
// missing material or substrate size, and duplicate probe names.
void ParseThermalSection(YamlMap& top, ThermalSection* out);
// Loads the deposit's and the substrate's materials (LoadThermalMaterial, relative paths against `scenario_dir`).
// Throws InputError naming the scenario key, then the material's own message (an unknown name lists the known ones).
void LoadThermalMaterials(const std::filesystem::path& scenario_dir, ThermalSection* thermal);
// Loads thermal.shape.bead_model (relative paths against `scenario_dir`). Throws InputError naming the key, then
// the model file's own message.
void LoadThermalShape(const std::filesystem::path& scenario_dir, ThermalSection* thermal);
// The rules across the process and thermal sections: an interpass max_c needs a thermal section and must lie above
// thermal.ambient_c; interpass.at: {probe: NAME} names one of thermal.probes; a thermal section needs process.arc.
// Throws InputError naming the key.
void CheckThermalScenario(const planner::ProcessSettings& process, const ThermalSection& thermal);
}  // namespace waam::analysis::internal
