// The thermal material files and their reader: every shipped file loads, is cited and covers the melt; broken
// files are refused with one message naming the file, the row or key and the rule.
#include "analysis/thermal_material_io.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/csv.h"
#include "models/core/error.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

const char* const kMaterialHead =
    "# name: test_metal\n"
    "# solidus_c: 1400 | a citation\n"
    "# liquidus_c: 1450\n"
    "# latent_heat_j_kg: 250000\n"
    "# emissivity: 0.5\n"
    "# [1] A reference.\n";
const char* const kMaterialColumns = "temperature_c,conductivity_w_mk,density_kg_m3,specific_heat_j_kgk\n";
const char* const kMaterialRows = "20,50,7800,450\n1000,30,7500,650\n";  // lines 8 and 9

std::string MaterialText(const std::string& from = "", const std::string& to = "") {
  std::string text = std::string(kMaterialHead) + kMaterialColumns + kMaterialRows;
  if (!from.empty()) text.replace(text.find(from), from.size(), to);
  return text;
}

std::string MaterialError(const std::string& text) {
  try {
    (void)ParseThermalMaterial(text, "m.csv", "m");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ThermalMaterialIo, ShipsTheFourMaterialsTheIssueNames) {
  const std::vector<std::string> known = KnownThermalMaterials();
  for (const char* name : {"mild_steel", "ss316l", "ti6al4v", "al5356"}) {
    EXPECT_THAT(known, ::testing::Contains(name)) << "models/data/materials/" << name << ".csv is missing";
  }
}

// Each shipped table runs from room temperature to above the liquidus, every row and scalar carries a citation,
// and the values are physical (the reader's own checks passed on load).
TEST(ThermalMaterialIo, EveryShippedMaterialIsCitedAndCoversTheMelt) {
  for (const std::string& name : KnownThermalMaterials()) {
    SCOPED_TRACE(name);
    const models::ThermalMaterial m = LoadThermalMaterial(name, fs::current_path());
    EXPECT_EQ(m.name, name);
    EXPECT_LE(m.temperature_c.front(), 25.0) << "the table must start at room temperature";
    EXPECT_GT(m.temperature_c.back(), m.liquidus_c) << "the table must reach above the liquidus";
    EXPECT_GT(m.latent_heat_j_kg, 0.0);
    EXPECT_GT(m.emissivity, 0.0);
    EXPECT_THAT(m.source, HasSubstr("[1]")) << "the file must list its references";
    const fs::path file = fs::path(WAAM_SOURCE_DIR) / "models" / "data" / "materials" / (name + ".csv");
    const CsvTable table = CsvTable::Read(file);
    for (const std::string& source : table.Strings("source")) EXPECT_FALSE(source.empty()) << "uncited row";
    int cited_keys = 0;
    for (const std::string& line : table.provenance()) {
      for (const char* key : {"solidus_c:", "liquidus_c:", "latent_heat_j_kg:", "emissivity:"}) {
        if (line.find(key) != std::string::npos && line.find('|') != std::string::npos) ++cited_keys;
      }
    }
    EXPECT_EQ(cited_keys, 4) << "each scalar key line must carry '| citation'";
  }
}

// The reader hands the table to ThermalMaterial unchanged: the interpolation returns the rows at their temperatures
// and the mean in between; the latent heat appears only in the melting range.
TEST(ThermalMaterialIo, ParsedTableInterpolatesBetweenItsRows) {
  const models::ThermalMaterial m = ParseThermalMaterial(MaterialText(), "m.csv", "m");
  EXPECT_EQ(m.name, "test_metal");
  EXPECT_EQ(m.source, "[1] A reference.");
  EXPECT_DOUBLE_EQ(m.Conductivity(20.0), 50.0);
  EXPECT_DOUBLE_EQ(m.Conductivity(510.0), 40.0);
  EXPECT_DOUBLE_EQ(m.SpecificHeat(2000.0), 650.0);
  EXPECT_DOUBLE_EQ(m.solidus_c, 1400.0);
  EXPECT_DOUBLE_EQ(m.EffectiveHeatCapacity(1425.0), 7500.0 * 650.0 + 7500.0 * 250000.0 / 50.0);
  EXPECT_DOUBLE_EQ(m.EffectiveHeatCapacity(1300.0), 7500.0 * 650.0);
}

TEST(ThermalMaterialIo, UnknownNameListsTheKnownOnes) {
  try {
    (void)LoadThermalMaterial("unobtainium", fs::current_path());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown material 'unobtainium'"));
    EXPECT_THAT(e.what(), HasSubstr("mild_steel"));
    EXPECT_THAT(e.what(), HasSubstr("ti6al4v"));
  }
}

TEST(ThermalMaterialIo, UserFileIsFoundAgainstTheBaseFolder) {
  const fs::path dir = fs::temp_directory_path() / ("waam_material_io_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "mine.csv") << MaterialText("# name: test_metal\n", "");
  const models::ThermalMaterial m = LoadThermalMaterial("mine.csv", dir);
  EXPECT_EQ(m.name, "mine") << "without a name line the file's stem names the material";
  EXPECT_THAT([&] { (void)LoadThermalMaterial("other/none.csv", dir); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("none.csv not found")));
  fs::remove_all(dir);
}

TEST(ThermalMaterialIo, BrokenFilesNameTheRowOrKeyAndTheRule) {
  EXPECT_THAT(MaterialError(MaterialText("1000,30", "20,30")),
              HasSubstr("m.csv:9: column 'temperature_c': 20 does not exceed the previous row's 20: temperatures must "
                        "be strictly increasing"));
  EXPECT_THAT(MaterialError(MaterialText("1000,30", "10,30")), HasSubstr("m.csv:9: column 'temperature_c'"));
  EXPECT_THAT(MaterialError(MaterialText("1000,30,7500", "1000,-30,7500")),
              HasSubstr("m.csv:9: column 'conductivity_w_mk': -30 must be > 0"));
  EXPECT_THAT(MaterialError(MaterialText("7800,450", "0,450")),
              HasSubstr("m.csv:8: column 'density_kg_m3': 0 must be > 0"));
  EXPECT_THAT(MaterialError(MaterialText("7800,450", "7800,hot")),
              HasSubstr("m.csv:8: column 'specific_heat_j_kgk': 'hot' is not a number"));
  EXPECT_THAT(MaterialError(std::string(kMaterialHead) + "temperature_c,conductivity_w_mk,density_kg_m3\n20,50,7800\n"),
              HasSubstr("m.csv: no column 'specific_heat_j_kgk'"));
  EXPECT_THAT(MaterialError(MaterialText("density_kg_m3", "densty_kg_m3")), HasSubstr("unknown column 'densty_kg_m3'"));
  EXPECT_THAT(MaterialError(MaterialText("liquidus_c: 1450", "liquidus_c: 1350")),
              HasSubstr("m.csv: solidus_c = 1400 is above liquidus_c = 1350"));
  EXPECT_THAT(MaterialError(MaterialText("# emissivity: 0.5\n", "")), HasSubstr("m.csv: missing key 'emissivity'"));
  EXPECT_THAT(MaterialError(MaterialText("emissivity: 0.5", "emissivity: 1.5")), HasSubstr("must be in [0, 1]"));
  EXPECT_THAT(MaterialError(MaterialText("latent_heat_j_kg: 250000", "latent_heat_j_kg: lots")),
              HasSubstr("m.csv: key 'latent_heat_j_kg': 'lots' is not a number"));
  EXPECT_THAT(MaterialError(MaterialText("latent_heat_j_kg: 250000", "latent_heat_j_kg: -1")), HasSubstr("must be >= 0"));
  EXPECT_THAT(MaterialError(MaterialText("# emissivity: 0.5\n", "# emissivity: 0.5\n# emissivity: 0.6\n")),
              HasSubstr("key 'emissivity' is given twice"));
  EXPECT_THAT(MaterialError(std::string(kMaterialHead) + kMaterialColumns), HasSubstr("the property table has no rows"));
}

}  // namespace
}  // namespace waam::analysis
