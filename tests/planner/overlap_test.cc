// Tests of the bead overlap spacings against the dissertation's Table 9 (seed 003, eq. 3.15 and 3.17).
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "planner/path/layer_pattern.h"

namespace waam::planner {
namespace {

using ::testing::HasSubstr;

// Table 9 lists, per bead width, the spacings used in the experiments (rounded to 0.01-0.1 mm).
TEST(OverlapSpacing, MatchesDissertationTable9) {
  std::ifstream in(std::string(WAAM_SOURCE_DIR) + "/models/data/nguyen2022_table9_overlap.csv");
  ASSERT_TRUE(in) << "Table 9 CSV should be in the shared data folder";
  std::string line;
  int rows = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("no,", 0) == 0) continue;
    std::stringstream ss(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 10u) << line;
    const OverlapSpacing p = OverlapSpacingFor(OverlapModel::kProposed, v[3]);
    const OverlapSpacing e = OverlapSpacingFor(OverlapModel::kExisting, v[3]);
    EXPECT_NEAR(p.zigzag_mm, v[4], 0.05) << "row " << v[0] << ": l = 0.738 w";
    EXPECT_NEAR(p.contour_to_zigzag_mm, v[5], 0.01) << "row " << v[0] << ": d1 = 0.47 w (eq. 3.15)";
    EXPECT_NEAR(p.contour_to_contour_mm, v[6], 0.01) << "row " << v[0] << ": d2 = 0.5 w (eq. 3.17)";
    EXPECT_NEAR(e.zigzag_mm, v[7], 0.05);
    EXPECT_NEAR(e.contour_to_zigzag_mm, v[8], 0.05) << "existing model: 0.738 w everywhere";
    EXPECT_NEAR(e.contour_to_contour_mm, v[9], 0.05);
    EXPECT_DOUBLE_EQ(p.boundary_offset_mm, 0.5 * v[3]);
    ++rows;
  }
  EXPECT_EQ(rows, 3);
}

TEST(OverlapSpacing, RejectsNonPositiveWidth) {
  for (double w : {0.0, -1.0}) {
    try {
      OverlapSpacingFor(OverlapModel::kProposed, w);
      FAIL() << "expected InputError for w = " << w;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr("bead width"));
    }
  }
}

}  // namespace
}  // namespace waam::planner
