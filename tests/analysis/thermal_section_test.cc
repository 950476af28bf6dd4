// The thermal scenario keys: process.arc, process.interpass and the thermal: section load, take their defaults, and
// refuse what breaks their rules with the key and line named.
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/scenario.h"
#include "analysis/scenario_keys.h"
#include "models/core/error.h"
#include "planner/scenario/arc_settings.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

// A valid thermal scenario; `from` is replaced by `to` to break it. Lines: 11 arc, 12 interpass, 13 thermal,
// 14 material, 15 substrate, 16 probes.
std::string ThermalText(const std::string& from = "", const std::string& to = "") {
  std::string text =
      "name: t\n"
      "part:\n"
      "  generator: {type: box, size_mm: [60, 8, 4]}\n"
      "slicing: {layer_height_mm: 2}\n"
      "path:\n"
      "  pattern: zigzag\n"
      "  bead_width_mm: 6\n"
      "process:\n"
      "  travel_speed_mm_min: 400\n"
      "  wire_feed_mm_min: 3200\n"
      "  arc: {power_w: 2000}\n"
      "  interpass: {max_c: 200, at: {probe: plate}}\n"
      "thermal:\n"
      "  material: mild_steel\n"
      "  substrate: {size_mm: [100, 40, 10]}\n"
      "  probes: {plate: [0, 10, -2], wall: [0, 0, 3]}\n";
  if (!from.empty()) text.replace(text.find(from), from.size(), to);
  return text;
}

fs::path WriteScenario(const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("waam_thermal_section_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "s.yaml") << text;
  return dir / "s.yaml";
}

std::string ErrorOf(const std::string& text) {
  try {
    LoadScenario(WriteScenario(text));
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an InputError for:\n" << text;
  return "";
}

std::string ErrorOfValidate(const Scenario& scenario) {
  try {
    ValidateScenario(scenario);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected ValidateScenario to refuse the scenario";
  return "";
}

TEST(ThermalSection, LoadsWithDefaults) {
  const Scenario s = LoadScenario(WriteScenario(ThermalText()));
  EXPECT_TRUE(s.thermal.given);
  EXPECT_EQ(s.process.arc.power_w, 2000.0);
  EXPECT_EQ(s.process.arc.efficiency, 0.84);
  EXPECT_EQ(s.process.interpass.max_c, 200.0);
  EXPECT_EQ(s.process.interpass.at, planner::InterpassAt::kProbe);
  EXPECT_EQ(s.process.interpass.probe, "plate");
  EXPECT_EQ(s.thermal.deposit.material.name, "mild_steel");
  EXPECT_EQ(s.thermal.substrate.material.name, "mild_steel") << "the plate defaults to the deposit's metal";
  EXPECT_FALSE(s.thermal.substrate_centre_mm.has_value());
  EXPECT_EQ(s.thermal.cell_mm, 2.0);
  EXPECT_EQ(s.thermal.InitialC(), s.thermal.ambient_c);
  EXPECT_EQ(s.thermal.table_conductance_w_m2k, 0.0);
  ASSERT_EQ(s.thermal.probes.size(), 2u);
  EXPECT_EQ(s.thermal.probes[0].name, "plate");
  EXPECT_EQ(s.thermal.probes[1].p_mm, Eigen::Vector3d(0, 0, 3)) << "probes keep the file's order";
}

TEST(ThermalSection, HeatSourceKeysTakeTheirDefaultsAndValues) {
  const Scenario d = LoadScenario(WriteScenario(ThermalText()));
  EXPECT_EQ(d.thermal.heat_source, twin::HeatSourceShape::kDoubleEllipsoid);
  EXPECT_EQ(d.thermal.pool_depth_beads, 2.0);
  EXPECT_EQ(d.thermal.pool_front_widths, 0.5);
  EXPECT_EQ(d.thermal.pool_rear_widths, 2.0);
  EXPECT_EQ(d.thermal.liquid_conductivity_factor, 5.0);
  const Scenario s = LoadScenario(WriteScenario(ThermalText(
      "  material: mild_steel\n", "  material: mild_steel\n  heat_source: uniform_bead\n"
                                   "  pool: {depth_beads: 1.5, front_widths: 1, rear_widths: 3}\n"
                                   "  liquid_conductivity_factor: 1\n")));
  EXPECT_EQ(s.thermal.heat_source, twin::HeatSourceShape::kUniformBead);
  EXPECT_EQ(s.thermal.pool_depth_beads, 1.5);
  EXPECT_EQ(s.thermal.pool_front_widths, 1.0);
  EXPECT_EQ(s.thermal.pool_rear_widths, 3.0);
  EXPECT_EQ(s.thermal.liquid_conductivity_factor, 1.0);
  EXPECT_THAT(ErrorOf(ThermalText("  material: mild_steel\n", "  material: mild_steel\n  pool: {depth: 2}\n")),
              HasSubstr("thermal.pool.depth"));
  EXPECT_THAT(ErrorOf(ThermalText("  material: mild_steel\n",
                                  "  material: mild_steel\n  liquid_conductivity_factor: 0.5\n")),
              HasSubstr("s.yaml:15: thermal.liquid_conductivity_factor"));
}

TEST(ThermalSection, ArcPowerFromVoltageAndCurrent) {
  const Scenario s =
      LoadScenario(WriteScenario(ThermalText("arc: {power_w: 2000}", "arc: {voltage_v: 14.5, current_a: 120, "
                                                                      "efficiency: 0.8}")));
  EXPECT_DOUBLE_EQ(s.process.arc.power_w, 14.5 * 120);
  EXPECT_DOUBLE_EQ(s.process.arc.HeatW(), 0.8 * 14.5 * 120);
}

TEST(ThermalSection, RefusesBrokenKeysNamingThem) {
  EXPECT_THAT(ErrorOf(ThermalText("arc: {power_w: 2000}", "arc: {efficiency: 0.8}")),
              HasSubstr("s.yaml:11: process.arc: the arc has no power"));
  EXPECT_THAT(ErrorOf(ThermalText("arc: {power_w: 2000}", "arc: {voltage_v: 14}")),
              HasSubstr("process.arc: the arc has no power: give both voltage_v (V) and current_a (A)"));
  EXPECT_THAT(ErrorOf(ThermalText("arc: {power_w: 2000}", "arc: {power_w: 2000, current_a: 100}")),
              HasSubstr("process.arc.power_w: give power_w, or voltage_v and current_a, not both"));
  EXPECT_THAT(ErrorOf(ThermalText("  arc: {power_w: 2000}\n", "")),
              HasSubstr("s.yaml:13: thermal: the thermal model needs the arc's power"));
  EXPECT_THAT(ErrorOf(ThermalText("max_c: 200", "max_c: 15")),
              HasSubstr("s.yaml:12: process.interpass.max_c = 15: below the ambient temperature 20 degC"));
  EXPECT_THAT(ErrorOf(ThermalText("{probe: plate}", "{probe: nowhere}")),
              HasSubstr("process.interpass.at: probe 'nowhere' is not one of thermal.probes"));
  EXPECT_THAT(ErrorOf(ThermalText("{probe: plate}", "probe")), HasSubstr("name the probe, as at: {probe: NAME}"));
  EXPECT_THAT(ErrorOf(ThermalText("{probe: plate}", "hottest")),
              HasSubstr("process.interpass.at = 'hottest': unknown value, expected one of next_start, top_max, probe"));
  EXPECT_THAT(ErrorOf(ThermalText("max_c: 200, ", "")), HasSubstr("process.interpass has no max_c"));
  EXPECT_THAT(ErrorOf(ThermalText("material: mild_steel", "material: unobtainium")),
              HasSubstr("s.yaml:14: thermal.material: unknown material 'unobtainium'"));
  EXPECT_THAT(ErrorOf(ThermalText("{size_mm: [100, 40, 10]}", "{size_mm: [100, 40, 10], material: tin}")),
              HasSubstr("thermal.substrate.material: unknown material 'tin'"));
  EXPECT_THAT(ErrorOf(ThermalText("{size_mm: [100, 40, 10]}", "{centre_mm: [0, 0, -5]}")),
              HasSubstr("thermal.substrate: give size_mm: [x, y, z] (mm)"));
  EXPECT_THAT(ErrorOf(ThermalText("  material: mild_steel\n", "")), HasSubstr("thermal.material is missing"));
  EXPECT_THAT(ErrorOf(ThermalText("  material: mild_steel\n", "  material: mild_steel\n  cell_mm: 0\n")),
              HasSubstr("thermal.cell_mm = 0: must be in"));
  EXPECT_THAT(ErrorOf(ThermalText("wall: [0, 0, 3]", "wall: [0, 0]")), HasSubstr("thermal.probes.wall"));
  EXPECT_THAT(ErrorOf(ThermalText("  material: mild_steel\n", "  material: mild_steel\n  colour: red\n")),
              HasSubstr("thermal.colour"));
  // An interpass limit needs the thermal model that measures it.
  std::string no_thermal = ThermalText("{probe: plate}", "next_start");
  no_thermal = no_thermal.substr(0, no_thermal.find("thermal:"));
  no_thermal.replace(no_thermal.find("  arc: {power_w: 2000}\n"), 23, "");
  EXPECT_THAT(ErrorOf(no_thermal), HasSubstr("process.interpass.max_c: an interpass temperature needs the thermal "
                                             "model"));
}

TEST(ThermalSection, SetOverridesReachEveryTableKeyWithinItsRange) {
  const fs::path file = WriteScenario(ThermalText());
  const Scenario s = LoadScenario(file, {"thermal.cell_mm=4", "thermal.initial_c=60", "thermal.table.temperature_c=35",
                                         "thermal.table.conductance_w_m2k=100",
                                         "thermal.substrate.centre_mm=[0, 0, -5]", "thermal.pool.depth_beads=1.5",
                                         "thermal.emissivity=0.4", "thermal.shape.distortion=true"});
  EXPECT_EQ(s.thermal.cell_mm, 4.0);
  EXPECT_EQ(s.thermal.InitialC(), 60.0);
  EXPECT_EQ(s.thermal.TableC(), 35.0);
  EXPECT_EQ(s.thermal.table_conductance_w_m2k, 100.0);
  ASSERT_TRUE(s.thermal.substrate_centre_mm.has_value());
  EXPECT_EQ((*s.thermal.substrate_centre_mm)[2], -5.0);
  EXPECT_EQ(s.thermal.pool_depth_beads, 1.5);
  EXPECT_EQ(s.thermal.Emissivity(), 0.4);
  EXPECT_TRUE(s.thermal.shape.distortion);
  const Scenario d = LoadScenario(file, {"thermal.ambient_c=30"});
  EXPECT_EQ(d.thermal.InitialC(), 30.0) << "initial_c follows ambient_c when absent";
  EXPECT_EQ(d.thermal.TableC(), 30.0) << "the table's temperature follows ambient_c when absent";
  EXPECT_LT(d.thermal.Emissivity(), 0.0) << "absent: each material's own";
  try {
    LoadScenario(file, {"thermal.cell_mm=100"});
    FAIL() << "expected InputError past thermal.cell_mm's maximum";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("thermal.cell_mm = 100: must be in [0.1, 50]"));
  }
  EXPECT_THROW(LoadScenario(file, {"thermal.cel_mm=4"}), InputError);
}

TEST(ThermalSection, SettingsBuiltInCodeAreCheckedAgainstTheKeysLimits) {
  Scenario s = LoadScenario(WriteScenario(ThermalText()));
  EXPECT_NO_THROW(ValidateScenario(s));
  Scenario coarse = s;
  coarse.thermal.cell_mm = 0.0;
  EXPECT_THAT(ErrorOfValidate(coarse), HasSubstr("thermal.cell_mm = 0: must be in [0.1, 50]"));
  Scenario hot_table = s;
  hot_table.thermal.table_c = 5000.0;
  EXPECT_THAT(ErrorOfValidate(hot_table), HasSubstr("thermal.table.temperature_c = 5000: must be in [-50, 1000]"));
  Scenario thin = s;
  thin.thermal.substrate_size_mm = std::array<double, 3>{100.0, 40.0, 0.5};
  EXPECT_THAT(ErrorOfValidate(thin), HasSubstr("thermal.substrate.size_mm = 0.5: must be in [1, 10000]"));
  Scenario no_plate = s;
  no_plate.thermal.substrate_size_mm.reset();
  EXPECT_THAT(ErrorOfValidate(no_plate), HasSubstr("thermal.substrate.size_mm: missing"));
  Scenario wide_pool = s;
  wide_pool.thermal.pool_rear_widths = 50.0;
  EXPECT_THAT(ErrorOfValidate(wide_pool), HasSubstr("thermal.pool.rear_widths = 50"));
}

TEST(ThermalSection, ArcAndInterpassKeysComeFromTheirFieldTables) {
  // A file's value out of range names file, line and key.
  EXPECT_THAT(ErrorOf(ThermalText("arc: {power_w: 2000}", "arc: {voltage_v: 500, current_a: 100}")),
              HasSubstr("s.yaml:11: process.arc.voltage_v = 500: must be in [1, 200]"));
  EXPECT_THAT(ErrorOf(ThermalText("max_c: 200", "max_c: 5000")),
              HasSubstr("s.yaml:12: process.interpass.max_c = 5000: must be in [-273.15, 3000]"));
  // --set reaches the arc's and the interpass rule's keys, within the same ranges.
  const fs::path file = WriteScenario(ThermalText());
  const Scenario s = LoadScenario(file, {"process.arc.power_w=3000", "process.arc.efficiency=0.7",
                                         "process.interpass.min_layer_time_s=120", "process.interpass.max_c=150"});
  EXPECT_EQ(s.process.arc.power_w, 3000.0);
  EXPECT_DOUBLE_EQ(s.process.arc.HeatW(), 0.7 * 3000.0);
  EXPECT_EQ(s.process.interpass.min_layer_time_s, 120.0);
  EXPECT_EQ(s.process.interpass.max_c, 150.0);
  try {
    LoadScenario(file, {"process.arc.efficiency=1.5"});
    FAIL() << "expected InputError past process.arc.efficiency's maximum";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("process.arc.efficiency = 1.5: must be in [0.05, 1]"));
  }
  // Settings built in code are checked against the same limits.
  Scenario weak = s;
  weak.process.arc.efficiency = 0.0;
  EXPECT_THAT(ErrorOfValidate(weak), HasSubstr("process.arc.efficiency = 0: must be in [0.05, 1]"));
  Scenario strong = s;
  strong.process.arc.power_w = 5e6;
  EXPECT_THAT(ErrorOfValidate(strong), HasSubstr("process.arc.power_w = 5e+06: must be in [1, 1e+06]"));
  Scenario unpowered = s;
  unpowered.process.arc.power_w = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(ErrorOfValidate(unpowered), HasSubstr("process.arc: the arc has no power"));
  Scenario long_layer = s;
  long_layer.process.interpass.min_layer_time_s = -1.0;
  EXPECT_THAT(ErrorOfValidate(long_layer), HasSubstr("process.interpass.min_layer_time_s = -1: must be in [0, 86400]"));
  Scenario unnamed = s;
  unnamed.process.interpass.probe.clear();
  EXPECT_THAT(ErrorOfValidate(unnamed), HasSubstr("process.interpass.at = probe: name the probe"));
  planner::ProcessSettings defaults;
  EXPECT_NO_THROW(planner::ValidateArcAndInterpass(defaults.arc, defaults.interpass)) << "no arc, no limit: valid";
}

TEST(ThermalSection, ProbeNamesAreWordsAndUnique) {
  EXPECT_THAT(ErrorOf(ThermalText("wall: [0, 0, 3]", "plate: [0, 0, 3]")),
              HasSubstr("s.yaml:16: thermal.probes.plate: a second probe of this name"));
  EXPECT_THAT(ErrorOf(ThermalText("wall: [0, 0, 3]", "'a b': [0, 0, 3]")),
              HasSubstr("thermal.probes.a b: a probe name must be a non-empty word without '/' or spaces"));
}

}  // namespace
}  // namespace waam::analysis
