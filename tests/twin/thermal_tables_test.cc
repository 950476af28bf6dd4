// The property table's inverse searched from a hint gives exactly the binary search's temperature.
#include <gtest/gtest.h>

#include "tests/twin/thermal_test_util.h"
#include "twin/thermal/thermal_tables.h"

namespace waam::twin::internal {
namespace {

// Over the steel-like fixture's range (the mushy zone included, and beyond both ends of the table), for hints near
// and far from the answer, the hinted inverse returns the same double as the binary search, and it inverts Enthalpy.
TEST(ThermalTables, HintedInverseIsTheBinarySearchsInverse) {
  const ThermalPropertyTable table(testing::VaryingMaterial(), -100.0, 3500.0, 1.0, 20.0, 5.0);
  int compared = 0;
  for (double t = -150.0; t <= 3600.0; t += 0.37) {
    const double h = table.Enthalpy(t);
    const double exact = table.Temperature(h);
    for (double hint : {t, t - 3.0, t + 2.5, t - 40.0, t + 900.0, -1e4, 1e5}) {
      ASSERT_EQ(table.Temperature(h, hint), exact) << "T = " << t << " degC, hint " << hint << " degC";
      ++compared;
    }
    ASSERT_NEAR(exact, t, 1e-6 * std::max(1.0, std::abs(t))) << "the inverse of Enthalpy at " << t << " degC";
  }
  EXPECT_GT(compared, 50000);
}

}  // namespace
}  // namespace waam::twin::internal
