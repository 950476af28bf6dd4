// The scenario's optional `thermal:` section: the metals, the plate, the grid, the losses and the probes of the
// thermal model (`waam thermal`, docs/THERMAL.md "Commands and outputs").
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "models/bead/bead_temperature_model.h"
#include "models/core/field_table.h"
#include "models/thermal/material.h"
#include "twin/thermal/heat_source.h"
#include "twin/thermal/thermal_simulation.h"

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

// A clamp holding the plate down (thermal.clamps[]): its contact patch on the plate's top face, through which heat
// flows into the clamp, a steel mass bolted to the table and taken at the table's temperature (docs/THERMAL.md
// "Clamps"). No default conductance: clamp contact is a fitted or assumed parameter (see the docs).
struct ThermalClamp {
  std::array<double, 2> centre_mm = {0.0, 0.0};  // the patch's centre in the part frame, x and y, mm
  std::array<double, 2> size_mm = {0.0, 0.0};    // the patch along x and y, mm
  double conductance_w_m2k = 0.0;                // plate top to the clamp, W/(m^2 K) (required)
  std::optional<double> under_conductance_w_m2k; // the plate's bottom under the patch to the table; absent = table's
  std::string where;                             // "file:line: thermal.clamps[N]"
};

struct ThermalSection {
  bool given = false;                // the scenario has a thermal: section
  std::string where;                 // "file:line: thermal"
  ThermalMaterialChoice deposit;     // thermal.material: the wire's metal (required)
  ThermalMaterialChoice substrate;   // thermal.substrate.material (default: the deposit's)
  std::optional<std::array<double, 3>> substrate_size_mm;  // thermal.substrate.size_mm [x, y, z], mm (required)
  // thermal.substrate.centre_mm: the plate's centre in the part frame; absent = centred under the part, top at z = 0.
  std::optional<std::array<double, 3>> substrate_centre_mm;
  std::string substrate_where;       // "file:line: thermal.substrate"
  double cell_mm = 2.0;              // thermal.cell_mm: grid spacing near the deposit, mm
  double ambient_c = 20.0;           // thermal.ambient_c: air (and, by default, plate and table) temperature, degC
  std::optional<double> initial_c;   // thermal.initial_c: the plate's temperature at the start (absent: ambient), degC
  double convection_w_m2k = 10.0;    // thermal.convection_w_m2k: h on every exposed face, W/(m^2 K)
  std::optional<double> emissivity;  // thermal.emissivity: of every exposed face; absent = each material's own
  double table_conductance_w_m2k = 0.0;  // thermal.table.conductance_w_m2k: plate-table contact (0 = no table)
  std::optional<double> table_c;     // thermal.table.temperature_c (absent: ambient), degC
  double table_thickness_mm = 0.0;   // thermal.table.thickness_mm: the table as a body under the plate (0 = a sink)
  double table_margin_mm = 0.0;      // thermal.table.margin_mm: how far that body reaches beyond the plate, mm
  double sample_s = 1.0;             // thermal.sample_s: interval of the probe histories and interpass checks, s
  // thermal.heat_source and thermal.pool.*: the arc's heat source and its pool's semi-axes over the bead's size
  // (twin::ThermalSettings documents each); thermal.liquid_conductivity_factor: k above the liquidus times this.
  twin::HeatSourceShape heat_source = twin::HeatSourceShape::kDoubleEllipsoid;
  double pool_depth_beads = 2.0;
  double pool_front_widths = 0.5;
  double pool_rear_widths = 2.0;
  double liquid_conductivity_factor = 5.0;
  std::vector<ThermalProbe> probes;  // thermal.probes, in file order
  std::vector<ThermalClamp> clamps;  // thermal.clamps, in file order
  double clamp_conductance_factor = 1.0;  // thermal.clamp_conductance_factor: each clamp conductance times this
  ThermalShape shape;                // thermal.shape

  // The plate's temperature at the start, degC (thermal.initial_c, or the ambient).
  double InitialC() const { return initial_c.value_or(ambient_c); }
  // The table's temperature, degC (thermal.table.temperature_c, or the ambient).
  double TableC() const { return table_c.value_or(ambient_c); }
  // The emissivity as twin::ThermalSettings takes it: < 0 = each material's own.
  double Emissivity() const { return emissivity.value_or(-1.0); }
};

// The plate as a box in the part frame, mm: thermal.substrate.size_mm around thermal.substrate.centre_mm, or, without
// a centre, centred under `beads_mm` (the planned or logged beads) with its top at z = 0.
Eigen::AlignedBox3d SubstrateBoxMm(const ThermalSection& thermal, const Eigen::AlignedBox3d& beads_mm);

// A metal as thermal.material and thermal.substrate.material name it (MemberField of each).
inline constexpr std::array kThermalMaterialFields = {
    OptField<&ThermalMaterialChoice::name_or_path>("material", "a shipped material's name or a material file"),
};
// One probe, thermal.probes.NAME: [x, y, z] (the value of NamesField's row).
inline constexpr std::array kThermalProbeFields = {
    NumField<&ThermalProbe::p_mm>("p_mm", "mm", -10000.0, 10000.0, "[x, y, z] in the part frame"),
};

// The keys of `thermal:` and its nested maps (models/core/field_table.h); analysis/thermal_section.cc reads the
// nested maps and the rules across keys (required keys, the substrate's material by default the deposit's).
inline constexpr std::array kThermalFields = {
    MemberField<&ThermalSection::deposit, kThermalMaterialFields>(
        "material", "the deposit's material: a shipped name or a file (required)"),
    CustomField<ThermalSection>("substrate", FieldType::kMap, "the plate (thermal.substrate)"),
    NumField<&ThermalSection::cell_mm>("cell_mm", "mm", 0.1, 50.0, "grid spacing near the deposit"),
    NumField<&ThermalSection::ambient_c>("ambient_c", "degC", -50.0, 200.0, "air temperature"),
    NumField<&ThermalSection::initial_c>("initial_c", "degC", -50.0, 1000.0,
                                         "the plate's temperature at the start; absent = ambient_c"),
    NumField<&ThermalSection::convection_w_m2k>("convection_w_m2k", "W/(m^2 K)", 0.0, 10000.0,
                                                "h on every exposed face"),
    NumField<&ThermalSection::emissivity>("emissivity", "", 0.0, 1.0,
                                          "of every exposed face; absent = each material's"),
    CustomField<ThermalSection>("table", FieldType::kMap, "contact with the table (thermal.table)"),
    NumField<&ThermalSection::sample_s>("sample_s", "s", 0.01, 600.0, "interval of the probe histories"),
    NamesField<&ThermalSection::probes, kThermalProbeFields, 0>("probes", "probe",
                                                                "NAME: [x, y, z] in the part frame"),
    CustomField<ThermalSection>("clamps", FieldType::kList, "contact patches on the plate's top (thermal.clamps[])"),
    NumField<&ThermalSection::clamp_conductance_factor>("clamp_conductance_factor", "", 0.0, 1000.0,
                                                        "every clamp's conductance_w_m2k times this (the factor "
                                                        "waam fit thermal --free clamps fits)"),
    OptField<&ThermalSection::heat_source>("heat_source", "the arc's heat source (docs/THERMAL.md)"),
    CustomField<ThermalSection>("pool", FieldType::kMap, "the double ellipsoid's semi-axes (thermal.pool)"),
    NumField<&ThermalSection::liquid_conductivity_factor>("liquid_conductivity_factor", "", 1.0, 100.0,
                                                          "k above the liquidus times this"),
    CustomField<ThermalSection>("shape", FieldType::kMap, "the heat shapes bead and distortion (thermal.shape)"),
};
inline constexpr std::array kThermalSubstrateFields = {
    NumField<&ThermalSection::substrate_size_mm>("size_mm", "mm", 1.0, 10000.0, "[x, y, z] of the plate (required)"),
    NumField<&ThermalSection::substrate_centre_mm>("centre_mm", "mm", -10000.0, 10000.0,
                                                   "its centre; absent = under the part, top at z = 0"),
    MemberField<&ThermalSection::substrate, kThermalMaterialFields>("material",
                                                                    "the plate's material (default: the deposit's)"),
};
inline constexpr std::array kThermalTableFields = {
    NumField<&ThermalSection::table_conductance_w_m2k>("conductance_w_m2k", "W/(m^2 K)", 0.0, 1.0e6,
                                                       "plate-table contact (required in table)"),
    NumField<&ThermalSection::table_c>("temperature_c", "degC", -50.0, 1000.0,
                                       "the table's temperature; absent = ambient_c"),
    NumField<&ThermalSection::table_thickness_mm>("thickness_mm", "mm", 0.0, 1000.0,
                                                  "the table as a body of this thickness under the plate; 0 = a "
                                                  "sink at temperature_c"),
    NumField<&ThermalSection::table_margin_mm>("margin_mm", "mm", 0.0, 5000.0,
                                               "how far the table body reaches beyond the plate on every side"),
};
inline constexpr std::array kThermalClampFields = {
    NumField<&ThermalClamp::centre_mm>("centre_mm", "mm", -10000.0, 10000.0,
                                       "[x, y] of the patch's centre in the part frame (required)"),
    NumField<&ThermalClamp::size_mm>("size_mm", "mm", 0.01, 10000.0, "[x, y] of the patch (required)"),
    NumField<&ThermalClamp::conductance_w_m2k>("conductance_w_m2k", "W/(m^2 K)", 0.0, 1.0e6,
                                               "plate top to the clamp at the table's temperature (required)"),
    NumField<&ThermalClamp::under_conductance_w_m2k>("under_conductance_w_m2k", "W/(m^2 K)", 0.0, 1.0e6,
                                                     "the plate's underside below the patch to the table; absent = "
                                                     "thermal.table's"),
};
inline constexpr std::array kThermalPoolFields = {
    NumField<&ThermalSection::pool_depth_beads>("depth_beads", "", 0.1, 20.0, "depth b over the bead height"),
    NumField<&ThermalSection::pool_front_widths>("front_widths", "", 0.05, 20.0,
                                                 "c_f ahead of the arc over the bead width"),
    NumField<&ThermalSection::pool_rear_widths>("rear_widths", "", 0.05, 20.0, "c_r behind the arc over the bead width"),
};
inline constexpr std::array kThermalShapeFields = {
    // A path kept as written (LoadThermalShape takes it from the scenario's folder), shown as a file in the docs.
    [] {
      Field<ThermalShape> f = OptField<&ThermalShape::bead_model_path>(
          "bead_model", "bead-temperature model file (waam fit bead-temperature); absent = planned beads");
      f.type = FieldType::kFile;
      return f;
    }(),
    OptField<&ThermalShape::distortion>("distortion",
                                        "inherent strains follow the layers' interpass and peak temperatures"),
};

// The clamps as the solver takes them. Throws InputError naming thermal.clamps[N] for a patch that reaches off the
// top face of `plate_mm` (the plate in the part frame).
std::vector<twin::ClampPatch> ClampPatches(const ThermalSection& thermal, const Eigen::AlignedBox3d& plate_mm);

// Throws InputError "thermal.<key> = value: must be in [min, max]" for a number of a given thermal section outside
// its key's range, or "thermal.substrate.size_mm: missing" without the plate's size: the check of settings built or
// changed in code.
void ValidateThermalSection(const ThermalSection& thermal);

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
