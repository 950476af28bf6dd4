// The scenario's `simulation` section: defaults, values, and errors naming the key.
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "analysis/scenario.h"

namespace waam::planner {
namespace {

using ::testing::HasSubstr;

std::filesystem::path WriteScenario(const std::string& name, const std::string& simulation) {
  const std::filesystem::path path = std::filesystem::path(::waam_test_env::TempDir()) / (name + ".yaml");
  std::ofstream out(path);
  out << "name: " << name << "\n"
      << "part: {generator: {type: box, size_mm: [20, 20, 10]}}\n"
      << "slicing: {layer_height_mm: 1.5}\n"
      << "path: {pattern: continuous, bead_width_mm: 6}\n"
      << "process: {travel_speed_mm_min: 400, wire_feed_mm_min: 3200}\n"
      << simulation;
  return path;
}

TEST(SimulationSection, DefaultsWhenAbsent) {
  const analysis::Scenario s = analysis::LoadScenario(WriteScenario("sim_default", ""));
  EXPECT_DOUBLE_EQ(s.simulation.voxel_mm, 0.5);
  EXPECT_EQ(NameOf(s.simulation.blend), "speed");
}

TEST(SimulationSection, ReadsValues) {
  const analysis::Scenario s = analysis::LoadScenario(WriteScenario(
      "sim_values", "simulation: {voxel_mm: 0.25, blend: fixed, blend_radius_mm: 3, start_length_mm: 12,\n"
                    "             max_voxels: 5000000}\n"));
  EXPECT_DOUBLE_EQ(s.simulation.voxel_mm, 0.25);
  EXPECT_EQ(NameOf(s.simulation.blend), "fixed");
  EXPECT_DOUBLE_EQ(s.simulation.blend_radius_mm, 3.0);
  EXPECT_DOUBLE_EQ(s.simulation.start_length_mm, 12.0);
  EXPECT_EQ(s.simulation.max_voxels, 5000000u);
}

TEST(SimulationSection, ErrorsNameTheKey) {
  try {
    analysis::LoadScenario(WriteScenario("sim_bad", "simulation: {voxel_mm: 5}\n"));
    FAIL() << "expected InputError for voxel_mm = 5";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("simulation.voxel_mm"));
  }
  try {
    analysis::LoadScenario(WriteScenario("sim_unknown", "simulation: {voxel_size: 0.5}\n"));
    FAIL() << "expected InputError for an unknown key";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("voxel_size"));
  }
}

}  // namespace
}  // namespace waam::planner
