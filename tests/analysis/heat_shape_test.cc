// Heat into shape at the analysis boundary: `waam fit bead-temperature` through the executable recovers the
// demonstration table's slope, thermal.shape loads its model, and the thermal run's layers become the twin's data.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "analysis/compensate_heat.h"
#include "analysis/scenario.h"
#include "models/bead/bead_temperature_model.h"
#include "models/core/error.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path HeatShapeDir() {
  const fs::path dir = fs::temp_directory_path() / ("waam_heat_shape_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

int HeatShapeWaam(const std::string& args, std::string* output) {
  FILE* pipe = popen((std::string(WAAM_BINARY) + " " + args + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return -1;
  char buffer[4096];
  while (fgets(buffer, sizeof buffer, pipe) != nullptr) *output += buffer;
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(HeatShapeCli, FitBeadTemperatureRecoversTheSlopeOfASeededTable) {
  // h = 1.3 (1 - 5e-4 (T - 60)), w = 5.0 (1 + 2e-4 (T - 60)), noise 0.01 mm (seed 7).
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  const fs::path csv = HeatShapeDir() / "beads.csv";
  {
    std::ofstream out(csv);
    out << "# synthetic beads for the test\nT_c,h,w\n";
    for (double t = 20.0; t <= 420.0; t += 20.0) {
      out << t << "," << 1.3 * (1.0 - 5e-4 * (t - 60.0)) + noise(rng) << ","
          << 5.0 * (1.0 + 2e-4 * (t - 60.0)) + noise(rng) << "\n";
    }
  }
  const fs::path model = HeatShapeDir() / "bt.json";
  std::string output;
  ASSERT_EQ(HeatShapeWaam("fit bead-temperature " + csv.string() + " --columns temperature=T_c,height=h,width=w "
                 "--reference-c 60 -o " + model.string(), &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("T_ref = 60 degC"));
  const models::BeadTemperatureModel m = models::BeadTemperatureModel::Load(model);
  EXPECT_NEAR(m.params().height_per_k, -5e-4, 3e-5);
  EXPECT_NEAR(m.params().width_per_k, 2e-4, 1e-5);
  EXPECT_EQ(m.HeightFactor(60.0), 1.0);
  EXPECT_EQ(m.fit().data.provenance.size(), 1u) << "the CSV's '#' line travels with the model";
}

TEST(HeatShapeScenario, ShapeKeysLoadTheModelAndDefaultOff) {
  const fs::path dir = HeatShapeDir();
  const std::string base =
      "name: t\npart:\n  generator: {type: box, size_mm: [60, 8, 4]}\nslicing: {layer_height_mm: 2}\n"
      "path:\n  pattern: zigzag\n  bead_width_mm: 6\nprocess:\n  travel_speed_mm_min: 400\n"
      "  wire_feed_mm_min: 3200\n  arc: {power_w: 2000}\nthermal:\n  material: mild_steel\n"
      "  substrate: {size_mm: [100, 40, 10]}\n";
  std::ofstream(dir / "off.yaml") << base;
  const Scenario off = LoadScenario(dir / "off.yaml");
  EXPECT_FALSE(off.thermal.shape.Any());
  fs::copy_file(fs::path(WAAM_SOURCE_DIR) / "scenarios/tubes/bead_temperature_demo.json", dir / "bt.json",
                fs::copy_options::overwrite_existing);
  std::ofstream(dir / "on.yaml") << base << "  shape: {bead_model: bt.json, distortion: true}\n";
  const Scenario on = LoadScenario(dir / "on.yaml");
  ASSERT_TRUE(on.thermal.shape.bead_model.has_value());
  EXPECT_TRUE(on.thermal.shape.distortion);
  EXPECT_EQ(on.thermal.shape.bead_model->HeightFactor(on.thermal.shape.bead_model->params().reference_c), 1.0);
  std::ofstream(dir / "bad.yaml") << base << "  shape: {bead_modle: bt.json}\n";
  EXPECT_THAT([&] { LoadScenario(dir / "bad.yaml"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("bead_modle")));
}

TEST(HeatShapeScenario, LayersWithoutATemperatureTakeThePlatesAndAreFullyHeated) {
  const std::vector<twin::LayerHeat> heat = LayerHeatOf({NAN, 250.0}, {1500.0, NAN}, 35.0);
  ASSERT_EQ(heat.size(), 2u);
  EXPECT_EQ(heat[0].interpass_c, 35.0);
  EXPECT_EQ(heat[0].peak_c, 1500.0);
  EXPECT_EQ(heat[1].interpass_c, 250.0);
  EXPECT_TRUE(std::isinf(heat[1].peak_c));
}

}  // namespace
}  // namespace waam::analysis
