// Tests of the `waam check` outputs on hand-built plans: check.json fields, the program files and the pictures.
#include "analysis/check_command.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/twin/test_plans.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

class CheckCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("waam_check_command_test_" + std::to_string(::getpid()));
    scenario_.name = "wall";
  }
  void TearDown() override { fs::remove_all(dir_); }
  nlohmann::json Run() {
    CheckOptions options;
    options.out_dir = dir_;
    options.quiet = true;
    RunCheckOnPlan(scenario_, twin::testing::RectangleWall(4, 80.0, 40.0, 2.0, 400.0 / 60.0), options);
    std::ifstream in(dir_ / "check.json");
    return nlohmann::json::parse(in);
  }
  static std::string Read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  fs::path dir_;
  Scenario scenario_;
};

TEST_F(CheckCommandTest, WellPlacedWallWritesEveryOutput) {
  const nlohmann::json j = Run();
  EXPECT_TRUE(j.at("ok").get<bool>()) << j.dump(2);
  EXPECT_EQ(j.at("points").get<int>(), 20);
  EXPECT_TRUE(j.at("violations").empty());
  EXPECT_GT(j.at("min_joint_margin_deg").get<double>(), 2.0);
  EXPECT_GT(j.at("max_joint_speed_ratio").get<double>(), 0.0);
  EXPECT_LT(j.at("max_joint_speed_ratio").get<double>(), 1.0);
  ASSERT_EQ(j.at("layers").size(), 4u);
  EXPECT_DOUBLE_EQ(j.at("layers")[0].at("tilt_deg").get<double>(), 0.0) << "planar layers: the positioner stays level";
  for (const char* f : {"cell_worst.png", "joints.png", "program.csv", "program.ls", "viewer.html"}) {
    EXPECT_TRUE(fs::exists(dir_ / f)) << f;
    EXPECT_GT(fs::file_size(dir_ / f), 100u) << f;
  }
  // One CSV row per path point.
  std::istringstream csv(Read(dir_ / "program.csv"));
  std::string line;
  int rows = -1;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 20);
  EXPECT_THAT(Read(dir_ / "program.ls"), HasSubstr("/PROG  WALL"));
}

TEST_F(CheckCommandTest, TorchIntoThePlateIsACollisionWithItsBodies) {
  scenario_.cell.part_offset_mm = {0.0, 0.0, -30.0};
  const nlohmann::json j = Run();
  EXPECT_FALSE(j.at("ok").get<bool>());
  ASSERT_FALSE(j.at("violations").empty());
  const nlohmann::json& v = j.at("violations").front();
  EXPECT_EQ(v.at("kind"), "collision");
  EXPECT_EQ(v.at("bodies"), nlohmann::json({"substrate", "torch"}));
  EXPECT_GT(v.at("penetration_mm").get<double>(), 10.0) << "the nozzle sits 15 mm above a TCP 30 mm deep";
  EXPECT_TRUE(v.contains("point"));
  EXPECT_TRUE(v.contains("layer"));
}

}  // namespace
}  // namespace waam::analysis
