// The `thermal:` scenario section: metals, plate, grid, losses and probes of the thermal model.
#include "analysis/thermal_settings.h"

#include "analysis/thermal_material_io.h"
#include "models/core/error.h"
#include "planner/scenario/scenario.h"
#include "models/core/yaml_map.h"

namespace waam::analysis::internal {

namespace {

Eigen::Vector3d Vec3(YamlMap& map, const std::string& key, double min, double max) {
  const std::vector<double> v = map.Numbers(key, 3, min, max);
  return {v[0], v[1], v[2]};
}

void ParseSubstrate(YamlMap& thermal, ThermalSection* out) {
  WAAM_THROW_UNLESS(thermal.Has("substrate"), thermal.Where("") << ": thermal.substrate is missing: give the plate "
                                                                   "as substrate: {size_mm: [x, y, z]}");
  YamlMap plate = thermal.Map("substrate");
  out->substrate_where = plate.Where("");
  WAAM_THROW_UNLESS(plate.Has("size_mm"), out->substrate_where << ": give size_mm: [x, y, z] (mm)");
  out->substrate_size_mm = Vec3(plate, "size_mm", 1.0, 10000.0);
  if (plate.Has("centre_mm")) out->substrate_centre_mm = Vec3(plate, "centre_mm", -10000.0, 10000.0);
  if (plate.Has("material")) {
    out->substrate.where = plate.Where("material");
    out->substrate.name_or_path = plate.String("material");
  } else {
    out->substrate.where = out->deposit.where;
    out->substrate.name_or_path = out->deposit.name_or_path;
  }
  plate.CheckNoUnknownKeys();
}

void ParseProbes(YamlMap& thermal, ThermalSection* out) {
  if (!thermal.Has("probes")) return;
  YamlMap probes = thermal.Map("probes");
  for (auto it = probes.node().begin(); it != probes.node().end(); ++it) {
    ThermalProbe probe;
    probe.name = it->first.Scalar();
    probe.where = probes.Where(probe.name);
    WAAM_THROW_UNLESS(!probe.name.empty() && probe.name.find_first_of("/ \t") == std::string::npos,
                      probe.where << ": a probe name must be a non-empty word without '/' or spaces");
    for (const ThermalProbe& other : out->probes) {
      WAAM_THROW_UNLESS(other.name != probe.name, probe.where << ": a second probe of this name");
    }
    probe.p_mm = Vec3(probes, probe.name, -10000.0, 10000.0);
    out->probes.push_back(std::move(probe));
  }
  probes.CheckNoUnknownKeys();
}

void ParseShape(YamlMap& thermal, ThermalSection* out) {
  if (!thermal.Has("shape")) return;
  YamlMap shape = thermal.Map("shape");
  if (shape.Has("bead_model")) {
    out->shape.bead_model_where = shape.Where("bead_model");
    out->shape.bead_model_path = shape.String("bead_model");
  }
  out->shape.distortion = shape.Bool("distortion", false);
  shape.CheckNoUnknownKeys();
}

}  // namespace

void ParseThermalSection(YamlMap& top, ThermalSection* out) {
  if (!top.Has("thermal")) return;
  YamlMap thermal = top.Map("thermal");
  out->given = true;
  out->where = thermal.Where("");
  WAAM_THROW_UNLESS(thermal.Has("material"), out->where << ": thermal.material is missing: name the deposit's metal "
                                                           "(e.g. mild_steel, ti6al4v, ss316l) or a material file");
  out->deposit.where = thermal.Where("material");
  out->deposit.name_or_path = thermal.String("material");
  ParseSubstrate(thermal, out);
  out->cell_mm = thermal.Number("cell_mm", 0.1, 50.0, out->cell_mm);
  out->ambient_c = thermal.Number("ambient_c", -50.0, 200.0, out->ambient_c);
  out->initial_c = thermal.Number("initial_c", -50.0, 1000.0, out->ambient_c);
  out->convection_w_m2k = thermal.Number("convection_w_m2k", 0.0, 10000.0, out->convection_w_m2k);
  out->emissivity = thermal.Has("emissivity") ? thermal.Number("emissivity", 0.0, 1.0) : -1.0;
  out->table_c = out->ambient_c;
  if (thermal.Has("table")) {
    YamlMap table = thermal.Map("table");
    out->table_conductance_w_m2k = table.Number("conductance_w_m2k", 0.0, 1.0e6);
    out->table_c = table.Number("temperature_c", -50.0, 1000.0, out->ambient_c);
    table.CheckNoUnknownKeys();
  }
  out->sample_s = thermal.Number("sample_s", 0.01, 600.0, out->sample_s);
  out->heat_source = thermal.Enum("heat_source", out->heat_source);
  if (thermal.Has("pool")) {
    YamlMap pool = thermal.Map("pool");
    out->pool_depth_beads = pool.Number("depth_beads", 0.1, 20.0, out->pool_depth_beads);
    out->pool_front_widths = pool.Number("front_widths", 0.05, 20.0, out->pool_front_widths);
    out->pool_rear_widths = pool.Number("rear_widths", 0.05, 20.0, out->pool_rear_widths);
    pool.CheckNoUnknownKeys();
  }
  out->liquid_conductivity_factor =
      thermal.Number("liquid_conductivity_factor", 1.0, 100.0, out->liquid_conductivity_factor);
  ParseProbes(thermal, out);
  ParseShape(thermal, out);
  thermal.CheckNoUnknownKeys();
}

void LoadThermalMaterials(const std::filesystem::path& scenario_dir, ThermalSection* thermal) {
  if (!thermal->given) return;
  for (ThermalMaterialChoice* choice : {&thermal->deposit, &thermal->substrate}) {
    try {
      choice->material = LoadThermalMaterial(choice->name_or_path, scenario_dir);
    } catch (const InputError& e) {
      WAAM_THROW(choice->where << ": " << e.what());
    }
  }
}

void LoadThermalShape(const std::filesystem::path& scenario_dir, ThermalSection* thermal) {
  if (thermal->shape.bead_model_path.empty()) return;
  std::filesystem::path path(thermal->shape.bead_model_path);
  if (path.is_relative()) path = scenario_dir / path;
  try {
    thermal->shape.bead_model = models::BeadTemperatureModel::Load(path);
  } catch (const InputError& e) {
    WAAM_THROW(thermal->shape.bead_model_where << ": " << e.what());
  }
}

void CheckThermalScenario(const planner::ProcessSettings& process, const ThermalSection& thermal) {
  const planner::InterpassSettings& interpass = process.interpass;
  if (interpass.HasMax()) {
    WAAM_THROW_UNLESS(thermal.given, interpass.max_where << ": an interpass temperature needs the thermal model: add "
                                                            "a thermal: section (docs/THERMAL.md)");
    WAAM_THROW_UNLESS(interpass.max_c > thermal.ambient_c,
                      interpass.max_where << " = " << interpass.max_c << ": below the ambient temperature "
                                          << thermal.ambient_c << " degC (thermal.ambient_c): the part never cools "
                                             "that far; must be above ambient");
  }
  if (interpass.at == planner::InterpassAt::kProbe) {
    bool found = false;
    for (const ThermalProbe& probe : thermal.probes) found = found || probe.name == interpass.probe;
    WAAM_THROW_UNLESS(found, interpass.at_where << ": probe '" << interpass.probe << "' is not one of thermal.probes");
  }
  if (thermal.given) {
    WAAM_THROW_UNLESS(process.arc.given, thermal.where << ": the thermal model needs the arc's power: add "
                                                          "process.arc: {power_w} or {voltage_v, current_a}");
  }
}

}  // namespace waam::analysis::internal
