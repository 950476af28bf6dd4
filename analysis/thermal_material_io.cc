// Reader of the thermal material files: '#' key lines for the scalars, one CSV row per tabulated temperature.
#include "analysis/thermal_material_io.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <map>
#include <sstream>

#include "models/core/csv.h"
#include "models/core/data_dir.h"
#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;

constexpr double kAbsoluteZeroC = -273.15;
constexpr std::array<const char*, 4> kNumberKeys = {"solidus_c", "liquidus_c", "latent_heat_j_kg", "emissivity"};
constexpr std::array<const char*, 5> kColumns = {"temperature_c", "conductivity_w_mk", "density_kg_m3",
                                                 "specific_heat_j_kgk", "source"};

fs::path MaterialsDir() { return DataDir() / "models" / "data" / "materials"; }

std::string Trim(std::string_view s) {
  const std::size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return "";
  const std::size_t e = s.find_last_not_of(" \t\r");
  return std::string(s.substr(b, e - b + 1));
}

bool IsKeyLine(const std::string& line, std::string* key, std::string* value) {
  const std::size_t colon = line.find(':');
  if (colon == std::string::npos || colon == 0) return false;
  const std::string k = Trim(std::string_view(line).substr(0, colon));
  if (k.empty() || !std::all_of(k.begin(), k.end(), [](char c) { return (c >= 'a' && c <= 'z') || c == '_'; })) {
    return false;
  }
  *key = k;
  *value = Trim(std::string_view(line).substr(colon + 1));
  return true;
}

// The '# key: value | citation' lines (name and the four scalars) and the '# [n] ...' reference lines.
struct Header {
  std::map<std::string, std::string> values;  // key -> value text (citation removed)
  std::vector<std::string> references;
};

Header ReadHeader(const CsvTable& table) {
  Header header;
  for (const std::string& raw : table.provenance()) {
    const std::string line = Trim(raw);
    if (line.rfind('[', 0) == 0) {
      header.references.push_back(line);
      continue;
    }
    std::string key, value;
    if (!IsKeyLine(line, &key, &value)) continue;
    const bool known = key == "name" ||
                       std::find_if(kNumberKeys.begin(), kNumberKeys.end(),
                                    [&](const char* k) { return key == k; }) != kNumberKeys.end();
    if (!known) continue;  // free comment lines may hold other "word: text" notes
    WAAM_THROW_UNLESS(header.values.count(key) == 0, table.source() << ": key '" << key << "' is given twice");
    header.values[key] = Trim(std::string_view(value).substr(0, value.find('|')));
  }
  return header;
}

double NumberKey(const Header& header, const std::string& source, const char* key) {
  const auto it = header.values.find(key);
  WAAM_THROW_UNLESS(it != header.values.end(),
                    source << ": missing key '" << key << "' (a line '# " << key << ": <value> | <citation>')");
  double value = 0.0;
  WAAM_THROW_UNLESS(ParseCsvNumber(it->second, /*allow_infinity=*/false, &value),
                    source << ": key '" << key << "': '" << it->second << "' is not a number");
  return value;
}

void CheckColumns(const CsvTable& table) {
  for (const std::string& column : table.header()) {
    const bool known = std::find_if(kColumns.begin(), kColumns.end(),
                                    [&](const char* c) { return column == c; }) != kColumns.end();
    WAAM_THROW_UNLESS(known, table.source() << ": unknown column '" << column
                                            << "' (expected temperature_c, conductivity_w_mk, density_kg_m3, "
                                               "specific_heat_j_kgk and optionally source)");
  }
  WAAM_THROW_UNLESS(table.rows() > 0, table.source() << ": the property table has no rows");
}

// Temperatures strictly increasing and above absolute zero: each property must be a function of temperature.
void CheckTemperatures(const CsvTable& table, const std::vector<double>& t) {
  for (std::size_t i = 0; i < t.size(); ++i) {
    WAAM_THROW_UNLESS(t[i] > kAbsoluteZeroC, table.source() << ":" << table.line(i) << ": column 'temperature_c': "
                                                           << t[i] << " degC is below absolute zero");
    if (i == 0) continue;
    WAAM_THROW_UNLESS(t[i] > t[i - 1], table.source()
                                           << ":" << table.line(i) << ": column 'temperature_c': " << t[i]
                                           << " does not exceed the previous row's " << t[i - 1]
                                           << ": temperatures must be strictly increasing (each property a "
                                              "function of temperature)");
  }
}

std::vector<double> PositiveColumn(const CsvTable& table, const char* column) {
  std::vector<double> values = table.Numbers(column);
  for (std::size_t i = 0; i < values.size(); ++i) {
    WAAM_THROW_UNLESS(values[i] > 0.0, table.source() << ":" << table.line(i) << ": column '" << column
                                                      << "': " << values[i] << " must be > 0");
  }
  return values;
}

void CheckScalars(const models::ThermalMaterial& m, const std::string& source) {
  WAAM_THROW_UNLESS(m.solidus_c > kAbsoluteZeroC && m.liquidus_c > kAbsoluteZeroC,
                    source << ": solidus_c and liquidus_c must be above absolute zero");
  WAAM_THROW_UNLESS(m.solidus_c <= m.liquidus_c, source << ": solidus_c = " << m.solidus_c
                                                        << " is above liquidus_c = " << m.liquidus_c
                                                        << ": the solidus must not exceed the liquidus");
  WAAM_THROW_UNLESS(m.latent_heat_j_kg >= 0.0,
                    source << ": latent_heat_j_kg = " << m.latent_heat_j_kg << " must be >= 0");
  WAAM_THROW_UNLESS(m.emissivity >= 0.0 && m.emissivity <= 1.0,
                    source << ": emissivity = " << m.emissivity << " must be in [0, 1]");
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::ostringstream out;
  for (std::size_t i = 0; i < names.size(); ++i) out << (i ? ", " : "") << names[i];
  return out.str();
}

}  // namespace

std::vector<std::string> KnownThermalMaterials() {
  std::vector<std::string> names;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(MaterialsDir(), error)) {
    if (entry.path().extension() == ".csv") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

models::ThermalMaterial ParseThermalMaterial(std::string_view text, const std::string& source,
                                             const std::string& default_name) {
  const CsvTable table = CsvTable::Parse(text, source);
  CheckColumns(table);
  const Header header = ReadHeader(table);
  models::ThermalMaterial m;
  const auto name = header.values.find("name");
  m.name = name != header.values.end() && !name->second.empty() ? name->second : default_name;
  for (std::size_t i = 0; i < header.references.size(); ++i) {
    m.source += (i ? " " : "") + header.references[i];
  }
  m.temperature_c = table.Numbers("temperature_c");
  CheckTemperatures(table, m.temperature_c);
  m.conductivity_w_mk = PositiveColumn(table, "conductivity_w_mk");
  m.density_kg_m3 = PositiveColumn(table, "density_kg_m3");
  m.specific_heat_j_kgk = PositiveColumn(table, "specific_heat_j_kgk");
  m.solidus_c = NumberKey(header, source, "solidus_c");
  m.liquidus_c = NumberKey(header, source, "liquidus_c");
  m.latent_heat_j_kg = NumberKey(header, source, "latent_heat_j_kg");
  m.emissivity = NumberKey(header, source, "emissivity");
  CheckScalars(m, source);
  return m;
}

models::ThermalMaterial LoadThermalMaterial(const std::string& name_or_path, const fs::path& base_dir) {
  const bool is_path = name_or_path.find('/') != std::string::npos ||
                       (name_or_path.size() > 4 && name_or_path.substr(name_or_path.size() - 4) == ".csv");
  fs::path path;
  if (is_path) {
    path = fs::path(name_or_path).is_absolute() ? fs::path(name_or_path) : base_dir / name_or_path;
    WAAM_THROW_UNLESS(fs::exists(path), "material file " << path.string() << " not found");
  } else {
    const std::vector<std::string> known = KnownThermalMaterials();
    WAAM_THROW_UNLESS(std::find(known.begin(), known.end(), name_or_path) != known.end(),
                      "unknown material '" << name_or_path << "': expected one of " << JoinNames(known)
                                           << ", or the path of a material .csv file");
    path = MaterialsDir() / (name_or_path + ".csv");
  }
  return ParseThermalMaterial(ReadFile(path), path.string(), path.stem().string());
}

}  // namespace waam::analysis
