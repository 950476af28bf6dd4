// `waam thermal` end to end on scenarios/thermal/wall_interpass.yaml: every output written and consistent with the
// others (timeline sums, interpass limit held, energy balance, probe histories in thermal.h5), the run step's
// metrics, and --help.
#include <hdf5.h>

#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using cli_test::ReadJson;
using cli_test::RunWaam;
using cli_test::TempDir;

std::string WallScenario() { return std::string(WAAM_SOURCE_DIR) + "/scenarios/thermal/wall_interpass.yaml"; }

// The scenario's thermal run, made once for the tests that read it (cli_test::SharedRun: once for all their
// processes).
const fs::path& WallRun() {
  static const fs::path out = cli_test::SharedRun("thermal " + WallScenario() + " -q");
  return out;
}

std::vector<double> ReadDoubles(hid_t file, const std::string& name) {
  const hid_t dataset = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(dataset, 0) << name;
  if (dataset < 0) return {};
  const hid_t space = H5Dget_space(dataset);
  std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Sclose(space);
  H5Dclose(dataset);
  return values;
}

// The same wall cut to 40 x 8 x 6 mm (three layers, still waiting for 200 degC): every output and the timeline sums
// do not need the six layers, and this is the run the sanitizer build checks (the six-layer tests run in Release).
TEST(ThermalCli, WritesEveryOutputAndTheTimelineAddsUp) {
  const fs::path out = TempDir("thermal_short_wall") / "out";
  std::string err;
  ASSERT_EQ(RunWaam("thermal " + WallScenario() + " -q --set part.generator.size_mm=[40,8,6] -o " + out.string(), &err),
            0)
      << err;
  for (const char* name : {"thermal.json", "thermal.h5", "interpass.png", "probes.png"}) {
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
  }
  const nlohmann::json j = ReadJson(out / "thermal.json");
  const nlohmann::json& t = j["timeline"];
  EXPECT_NEAR(t["total_s"].get<double>(),
              t["arc_on_s"].get<double>() + t["travel_s"].get<double>() + t["wait_s"].get<double>(), 1e-6);
  double arc = 0.0, travel = 0.0, wait = 0.0;
  for (const nlohmann::json& l : t["layers"]) {
    arc += l["arc_on_s"].get<double>();
    travel += l["travel_s"].get<double>();
    wait += l["wait_s"].get<double>();
  }
  EXPECT_NEAR(arc, t["arc_on_s"].get<double>(), 1e-6);
  EXPECT_NEAR(travel, t["travel_s"].get<double>(), 1e-6);
  EXPECT_NEAR(wait, t["wait_s"].get<double>(), 1e-6);
  EXPECT_GT(wait, 0.0) << "the short wall must still wait for 200 degC";
  EXPECT_EQ(j["build_time_s"], t["total_s"]);
  ASSERT_EQ(j["layers"].size(), t["layers"].size());
  for (std::size_t l = 0; l < j["layers"].size(); ++l) {
    char name[40];
    std::snprintf(name, sizeof(name), "maps/layer_%04zu.png", l);
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
  }
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    EXPECT_THAT(entry.path().string(), ::testing::Not(::testing::HasSubstr(".tmp-")));
  }
}

TEST(ThermalCli, WaitsHoldTheInterpassLimitAndTheEnergyBalanceCloses) {
  const nlohmann::json j = ReadJson(WallRun() / "thermal.json");
  const double max_c = j["interpass"]["max_c"].get<double>();
  double waits = 0.0;
  for (const nlohmann::json& l : j["layers"]) {
    const int layer = l["layer"].get<int>();
    SCOPED_TRACE(layer);
    waits += l["wait_s"].get<double>();
    // The layer starts in the timeline when the run started it, after its wait.
    EXPECT_NEAR(l["start_s"].get<double>(), j["timeline"]["layers"][layer]["start_s"].get<double>(), 1e-6);
    if (layer == 0) continue;
    EXPECT_LE(l["interpass_c"].get<double>(), max_c) << "the layer started above the interpass limit";
    EXPECT_GT(l["peak_c"].get<double>(), max_c);
  }
  EXPECT_GT(waits, 0.0) << "this wall must wait for 200 degC";
  EXPECT_NEAR(j["interpass_wait_s"].get<double>(), waits, 1e-9);
  EXPECT_GE(j["total_wait_s"].get<double>(), waits - 1e-9);
  const nlohmann::json& e = j["energy_balance"];
  EXPECT_NEAR(e["heat_input_j"].get<double>(), e["efficiency"].get<double>() * e["arc_energy_j"].get<double>(),
              1e-6 * e["heat_input_j"].get<double>());
  EXPECT_LT(e["relative_error"].get<double>(), 0.01);
  EXPECT_GT(j["solver"]["cells"].get<double>(), 0.0);
  EXPECT_GT(j["solver"]["steps"].get<double>(), 0.0);
}

TEST(ThermalCli, ProbeHistoriesInTheH5MatchTheJson) {
  const fs::path& out = WallRun();
  const nlohmann::json j = ReadJson(out / "thermal.json");
  const hid_t file = H5Fopen((out / "thermal.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const std::vector<double> time = ReadDoubles(file, "/probes/time_s");
  ASSERT_GT(time.size(), 10u);
  EXPECT_NEAR(time.back(), j["timeline"]["total_s"].get<double>(), 1e-6) << "the histories cover the whole build";
  for (const auto& [name, probe] : j["probes"].items()) {
    const std::vector<double> t = ReadDoubles(file, "/probes/" + name);
    ASSERT_EQ(t.size(), time.size()) << name;
    double max_c = -1e300, at = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (std::isfinite(t[i]) && t[i] > max_c) {
        max_c = t[i];
        at = time[i];
      }
    }
    EXPECT_DOUBLE_EQ(probe["max_c"].get<double>(), max_c) << name;
    EXPECT_DOUBLE_EQ(probe["time_of_max_s"].get<double>(), at) << name;
  }
  // The field at the last layer's end, with its geometry.
  const std::string last = "/fields/layer_000" + std::to_string(j["layers"].size() - 1);
  const hid_t dataset = H5Dopen2(file, last.c_str(), H5P_DEFAULT);
  ASSERT_GE(dataset, 0) << last;
  hsize_t dims[3] = {0, 0, 0};
  const hid_t space = H5Dget_space(dataset);
  H5Sget_simple_extent_dims(space, dims, nullptr);
  const hid_t attribute = H5Aopen(dataset, "dims", H5P_DEFAULT);
  double n[3] = {0, 0, 0};
  H5Aread(attribute, H5T_NATIVE_DOUBLE, n);
  EXPECT_EQ(dims[2], static_cast<hsize_t>(n[0]));
  EXPECT_EQ(dims[1], static_cast<hsize_t>(n[1]));
  EXPECT_EQ(dims[0], static_cast<hsize_t>(n[2]));
  H5Aclose(attribute);
  H5Sclose(space);
  H5Dclose(dataset);
  H5Fclose(file);
}

TEST(ThermalCli, RunStepReportsTheBuildTimeWaitsAndTemperatures) {
  const fs::path out = TempDir("thermal_run_step") / "out";
  std::string err;
  ASSERT_EQ(RunWaam("run " + WallScenario() + " --steps plan thermal -q --no-images -o " + out.string(), &err), 0)
      << err;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  const nlohmann::json& step = summary["steps"][1];
  EXPECT_EQ(step["name"], "thermal");
  const nlohmann::json thermal = ReadJson(WallRun() / "thermal.json");
  for (const char* metric : {"build_time_s", "total_wait_s", "max_interpass_c", "peak_c"}) {
    ASSERT_TRUE(step["metrics"].contains(metric)) << metric;
    EXPECT_DOUBLE_EQ(step["metrics"][metric].get<double>(), thermal[metric].get<double>())
        << metric << ": the step and the command compute the same build";
  }
}

TEST(ThermalCli, HelpNamesTheOutputs) {
  std::string err;
  const fs::path dir = TempDir("thermal_help");
  const int code = std::system((std::string(WAAM_BINARY) + " thermal --help > " + (dir / "help.txt").string()).c_str());
  EXPECT_EQ(WEXITSTATUS(code), 0);
  const std::string help = cli_test::Slurp(dir / "help.txt");
  for (const char* word : {"thermal.json", "thermal.h5", "interpass.png", "process.interpass", "probes {NAME"}) {
    EXPECT_THAT(help, ::testing::HasSubstr(word));
  }
}

}  // namespace
}  // namespace waam::analysis
