// `waam material`: the material reader's result, as the thermal model will use it, for a user to check a file.
#include "analysis/material_command.h"

#include <iostream>

#include <nlohmann/json.hpp>

#include "analysis/thermal_material_io.h"
#include "models/core/files.h"
#include "models/core/json_text.h"

namespace waam::analysis {

std::string ThermalMaterialJson(const models::ThermalMaterial& material) {
  nlohmann::ordered_json j;
  j["name"] = material.name;
  j["source"] = material.source;
  j["solidus_c"] = material.solidus_c;
  j["liquidus_c"] = material.liquidus_c;
  j["latent_heat_j_kg"] = material.latent_heat_j_kg;
  j["emissivity"] = material.emissivity;
  j["temperature_c"] = material.temperature_c;
  j["conductivity_w_mk"] = material.conductivity_w_mk;
  j["density_kg_m3"] = material.density_kg_m3;
  j["specific_heat_j_kgk"] = material.specific_heat_j_kgk;
  return JsonText(j) + "\n";
}

void RunMaterialCommand(const MaterialOptions& options) {
  const models::ThermalMaterial material = LoadThermalMaterial(options.material, std::filesystem::current_path());
  const std::string json = ThermalMaterialJson(material);
  if (!options.out_dir.empty()) {
    EnsureOutputDirectory(options.out_dir);
    WriteFileAtomic(options.out_dir / "material.json", json);
  }
  if (!options.quiet) std::cout << json;
}

}  // namespace waam::analysis
