// The cell check on 1 and 4 threads: the collision pass runs in chunks in parallel, the report must not change.
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/files.h"
#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {

namespace fs = std::filesystem;

// `waam check` of `scenario` on `threads` threads: its check.json and program.csv.
std::pair<std::string, std::string> Check(const std::string& scenario, int threads, const std::string& name) {
  const fs::path out = cli_test::TempDir(name);
  std::string err;
  const int code = cli_test::RunWaam("check " + (fs::path(WAAM_SOURCE_DIR) / scenario).string() + " -o " +
                                         out.string() + " -q --no-images --threads " + std::to_string(threads),
                                     &err);
  EXPECT_TRUE(code == 0 || code == 3) << err;
  return {ReadFile(out / "check.json"), ReadFile(out / "program.csv")};
}

TEST(ParallelCheck, SameCheckJsonOnOneAndFourThreads) {
  // The torch into the plate: thousands of samples (several chunks), collisions across chunk boundaries.
  for (const char* scenario : {"scenarios/cell/cell_torch_into_plate.yaml", "scenarios/cell/cell_joint_limit.yaml"}) {
    const auto one = Check(scenario, 1, "check_t1");
    const auto four = Check(scenario, 4, "check_t4");
    EXPECT_EQ(one.first, four.first) << scenario << ": check.json differs between 1 and 4 threads";
    EXPECT_EQ(one.second, four.second) << scenario << ": program.csv differs";
    EXPECT_NE(one.first.find("\"violations\""), std::string::npos);
  }
}

}  // namespace
}  // namespace waam::analysis
