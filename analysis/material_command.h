// `waam material`: loads a thermal material (a shipped name or a user's file), checks it and reports it as JSON.
#pragma once

#include <filesystem>
#include <string>

#include "models/thermal/material.h"

namespace waam::analysis {

struct MaterialOptions {
  std::string material;             // a name from models/data/materials or the path of a material .csv file
  std::filesystem::path out_dir;    // empty: print only; else write out_dir/material.json (atomically)
  bool quiet = false;               // no JSON on stdout
};

// The material as JSON: name, source, the scalars and the table (degC, W/(m K), kg/m^3, J/(kg K)).
std::string ThermalMaterialJson(const models::ThermalMaterial& material);

// Loads options.material (relative paths against the current folder), prints its JSON unless quiet and writes it
// to out_dir/material.json when out_dir is given. Throws InputError for a file the reader refuses (nothing is
// written then).
void RunMaterialCommand(const MaterialOptions& options);

}  // namespace waam::analysis
