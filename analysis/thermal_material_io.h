// Reads a metal's temperature-dependent thermal properties from a cited CSV data file (models/data/materials).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "models/thermal/material.h"

namespace waam::analysis {

// The names of the materials shipped in DataDir()/models/data/materials (the .csv file stems), sorted.
std::vector<std::string> KnownThermalMaterials();

// Loads a material by `name_or_path`: a shipped name (e.g. "mild_steel", see KnownThermalMaterials) or the path of
// a user's own file in the same format (anything with a '/' or ending in ".csv"; relative paths are taken against
// `base_dir`, usually the scenario's folder). The format is described in docs/THERMAL.md ("Materials").
// Throws InputError naming the file and the row (line) or key for: an unknown name (listing the known ones), a
// missing file, a missing or unknown column or key, text in a number, a temperature column that is not strictly
// increasing, a property <= 0, solidus above liquidus, a negative latent heat, an emissivity outside [0, 1].
models::ThermalMaterial LoadThermalMaterial(const std::string& name_or_path, const std::filesystem::path& base_dir);

// Parses the text of a material file; `source` names it in messages and `default_name` is the material's name when
// the file has no `# name:` line. Throws InputError as LoadThermalMaterial does.
models::ThermalMaterial ParseThermalMaterial(std::string_view text, const std::string& source,
                                             const std::string& default_name);

}  // namespace waam::analysis
