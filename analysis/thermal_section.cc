// The `thermal:` scenario section: metals, plate, grid, losses and probes of the thermal model.
#include "analysis/thermal_settings.h"

#include "analysis/thermal_material_io.h"
#include "models/core/error.h"
#include "planner/scenario/scenario.h"
#include "models/core/yaml_map.h"

namespace waam::analysis {

Eigen::AlignedBox3d SubstrateBoxMm(const ThermalSection& thermal, const Eigen::AlignedBox3d& beads_mm) {
  WAAM_DEMAND(thermal.substrate_size_mm.has_value());
  const std::array<double, 3>& s = *thermal.substrate_size_mm;
  const Eigen::Vector3d size(s[0], s[1], s[2]);
  Eigen::Vector3d centre(beads_mm.center().x(), beads_mm.center().y(), -0.5 * size.z());
  if (const auto& c = thermal.substrate_centre_mm) centre = Eigen::Vector3d((*c)[0], (*c)[1], (*c)[2]);
  return Eigen::AlignedBox3d(centre - 0.5 * size, centre + 0.5 * size);
}

std::vector<twin::ClampPatch> ClampPatches(const ThermalSection& thermal, const Eigen::AlignedBox3d& plate_mm) {
  std::vector<twin::ClampPatch> patches;
  const Eigen::Vector2d lo = plate_mm.min().head<2>(), hi = plate_mm.max().head<2>();
  constexpr double kToleranceMm = 1e-6;
  for (const ThermalClamp& clamp : thermal.clamps) {
    const Eigen::Vector2d centre(clamp.centre_mm[0], clamp.centre_mm[1]);
    const Eigen::Vector2d half(0.5 * clamp.size_mm[0], 0.5 * clamp.size_mm[1]);
    const Eigen::AlignedBox2d patch(centre - half, centre + half);
    const bool on_plate = (patch.min().array() >= lo.array() - kToleranceMm).all() &&
                          (patch.max().array() <= hi.array() + kToleranceMm).all();
    WAAM_THROW_UNLESS(on_plate, clamp.where << ": the patch (x " << patch.min().x() << " to " << patch.max().x()
                                            << ", y " << patch.min().y() << " to " << patch.max().y()
                                            << " mm) reaches off the plate's top face (x " << lo.x() << " to "
                                            << hi.x() << ", y " << lo.y() << " to " << hi.y()
                                            << " mm): a clamp's contact patch must lie on the plate");
    patches.push_back({patch, clamp.conductance_w_m2k * thermal.clamp_conductance_factor,
                       clamp.under_conductance_w_m2k.value_or(-1.0)});
  }
  return patches;
}

void ValidateThermalSection(const ThermalSection& thermal) {
  if (!thermal.given) return;
  WAAM_THROW_UNLESS(thermal.substrate_size_mm.has_value(), "thermal.substrate.size_mm: missing: give the plate's "
                                                           "size [x, y, z] (mm)");
  CheckFields<ThermalSection>(kThermalFields, thermal, "thermal");
  CheckFields<ThermalSection>(kThermalSubstrateFields, thermal, "thermal.substrate");
  CheckFields<ThermalSection>(kThermalTableFields, thermal, "thermal.table");
  WAAM_THROW_UNLESS(thermal.table_thickness_mm == 0.0 || thermal.table_conductance_w_m2k > 0.0,
                    "thermal.table.conductance_w_m2k = " << thermal.table_conductance_w_m2k << " with thickness_mm = "
                                                         << thermal.table_thickness_mm
                                                         << ": a table body needs a contact conductance > 0");
  CheckFields<ThermalSection>(kThermalPoolFields, thermal, "thermal.pool");
  for (std::size_t n = 0; n < thermal.clamps.size(); ++n) {
    CheckFields<ThermalClamp>(kThermalClampFields, thermal.clamps[n], "thermal.clamps[" + std::to_string(n) + "]");
  }
}

}  // namespace waam::analysis

namespace waam::analysis::internal {

namespace {

void ParseSubstrate(YamlMap& thermal, ThermalSection* out) {
  WAAM_THROW_UNLESS(thermal.Has("substrate"), thermal.Where("") << ": thermal.substrate is missing: give the plate "
                                                                   "as substrate: {size_mm: [x, y, z]}");
  YamlMap plate = thermal.Map("substrate");
  out->substrate_where = plate.Where("");
  WAAM_THROW_UNLESS(plate.Has("size_mm"), out->substrate_where << ": give size_mm: [x, y, z] (mm)");
  ReadFields<ThermalSection>(plate, kThermalSubstrateFields, out);
  if (plate.Has("material")) {
    out->substrate.where = plate.Where("material");
  } else {
    out->substrate.where = out->deposit.where;
    out->substrate.name_or_path = out->deposit.name_or_path;
  }
  plate.CheckNoUnknownKeys();
}

void ParseClamps(YamlMap& thermal, ThermalSection* out) {
  if (!thermal.Has("clamps")) return;
  for (YamlMap& map : thermal.Maps("clamps")) {
    ThermalClamp clamp;
    clamp.where = map.Where("");
    for (const char* key : {"centre_mm", "size_mm", "conductance_w_m2k"}) {
      ReadField<ThermalClamp>(map, kThermalClampFields, key, &clamp, true);
    }
    ReadField<ThermalClamp>(map, kThermalClampFields, "under_conductance_w_m2k", &clamp);
    map.CheckNoUnknownKeys();
    out->clamps.push_back(std::move(clamp));
  }
}

void ParseShape(YamlMap& thermal, ThermalSection* out) {
  if (!thermal.Has("shape")) return;
  YamlMap shape = thermal.Map("shape");
  if (shape.Has("bead_model")) out->shape.bead_model_where = shape.Where("bead_model");
  ReadFields<ThermalShape>(shape, kThermalShapeFields, &out->shape);
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
  ReadField<ThermalSection>(thermal, kThermalFields, "material", out);
  ParseSubstrate(thermal, out);
  ReadFields<ThermalSection>(thermal, kThermalFields, out);
  if (thermal.Has("table")) {
    YamlMap table = thermal.Map("table");
    table.Require("conductance_w_m2k");
    ReadFields<ThermalSection>(table, kThermalTableFields, out);
    WAAM_THROW_UNLESS(out->table_thickness_mm == 0.0 || out->table_conductance_w_m2k > 0.0,
                      table.Where("conductance_w_m2k") << " = 0 with thickness_mm = " << out->table_thickness_mm
                                                       << ": a table body needs a contact conductance > 0");
    table.CheckNoUnknownKeys();
  }
  ReadFieldMap<ThermalSection>(thermal, "pool", kThermalPoolFields, out);
  ParseClamps(thermal, out);
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
