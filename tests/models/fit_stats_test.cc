// Tests of the goodness-of-fit statistics and their JSON form.
#include "models/fit/fit_stats.h"

#include <cmath>

#include <gtest/gtest.h>

namespace waam::models {
namespace {

TEST(FitStatsTest, MatchesHandComputedValues) {
  // measured 1,2,3,4 (mean 2.5, SST 5); residuals 0.1,-0.1,0.2,-0.2 (SSE 0.1).
  const FitStats s = ComputeFitStats({1, 2, 3, 4}, {0.9, 2.1, 2.8, 4.2}, 2);
  EXPECT_EQ(s.n, 4u);
  EXPECT_NEAR(s.sse, 0.1, 1e-12);
  EXPECT_NEAR(s.r2, 1.0 - 0.1 / 5.0, 1e-12);
  EXPECT_NEAR(s.rmse, std::sqrt(0.1 / 4), 1e-12);
  EXPECT_NEAR(s.rmse_dof, std::sqrt(0.1 / 2), 1e-12) << "rmse_dof divides by n - p";
}

TEST(FitStatsTest, NoDegreesOfFreedomGivesNanAndJsonNull) {
  const FitStats s = ComputeFitStats({1, 2}, {1, 2}, 2);
  EXPECT_TRUE(std::isnan(s.rmse_dof));
  const nlohmann::json j = ToJson(s);
  EXPECT_TRUE(j["rmse_dof"].is_null()) << "JSON has no NaN";
  EXPECT_TRUE(std::isnan(FitStatsFromJson(j, "t").rmse_dof));
}

}  // namespace
}  // namespace waam::models
