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
#include "analysis/thermal_command.h"
#include "planner/plan_scenario.h"
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

TEST(HeatShapeScenario, BuildTimeCountsTheInterpassWaitsOfAContinuousSpiral) {
  // A small tube laid as one continuous spiral (no arc end between the turns) with a 250 degC interpass limit: the
  // thermal run pauses before the turns, and compensate.json's heat.build_time_s is the timeline with those pauses.
  const fs::path file = HeatShapeDir() / "spiral_interpass.yaml";
  std::ofstream(file) << "name: spiral_interpass\n"
                         "part:\n  generator: {type: bent_tube, diameter_mm: [24, 24], sides: [0, 0], wall_mm: 4,\n"
                         "    bend_radius_mm: 40, bend_angle_deg: 10, straight_mm: [4, 0]}\n"
                         "slicing: {type: skeleton, h_min_mm: 1.5, h_max_mm: 2.0, point_spacing_mm: 3}\n"
                         "path: {pattern: spiral}\n"
                         "process:\n  wire_feed_mm_min: 3200\n  wire_diameter_mm: 1.0\n  bead_model: speed_height\n"
                         "  arc: {voltage_v: 14.5, current_a: 125}\n  interpass: {max_c: 250, at: next_start}\n"
                         "thermal:\n  material: mild_steel\n  substrate: {size_mm: [60, 60, 8]}\n  cell_mm: 4.0\n"
                         "  table: {conductance_w_m2k: 200}\n  shape: {distortion: true}\n";
  const Scenario scenario = LoadScenario(file);
  const planner::Plan plan = planner::PlanScenario(scenario, nullptr).plan;
  twin::CompensationOptions loop;
  const nlohmann::json heat = PrepareHeatShape(scenario, plan, true, &loop);
  const double waits = heat["interpass_wait_s"].get<double>();
  EXPECT_GT(waits, 0.0) << "a 250 degC limit on a 4 mm wall must make the build wait";
  // The timeline without the waits: what the build time read before they were counted.
  const double plain = TimelineBuilderFor(scenario, plan)(std::vector<double>(plan.layers.size(), 0.0)).total_s;
  EXPECT_NEAR(heat["build_time_s"].get<double>(), plain + waits, 1e-6 * plain) << heat.dump();
}

}  // namespace
}  // namespace waam::analysis
