// Convergence of the thermal model under step and grid refinement on the semi-infinite body under a constant flux,
// with the observed orders computed from the errors against the erfc solution.
#include <cmath>

#include <gtest/gtest.h>

#include "tests/twin/thermal_test_util.h"

namespace waam::twin {
namespace {

using testing::RunColumn;

// Backward Euler is first order in time. On a 0.5 mm grid (spatial error ~0.005 K) the error after 20 s falls from
// about 1 K at dt = 0.4 s by half per halving: the observed order log2(e(dt) / e(dt/2)) must be within 0.8-1.2.
TEST(ThermalConvergence, TimeStepRefinementIsFirstOrder) {
  double previous = 0.0;
  for (double dt : {0.4, 0.2, 0.1}) {
    const double error = RunColumn(0.5, dt, 20.0, 100.0).max_error_k;
    if (previous > 0.0) {
      const double order = std::log2(previous / error);
      EXPECT_GT(order, 0.8) << "dt " << dt << " s: error " << error << " K after " << previous << " K";
      EXPECT_LT(order, 1.2) << "dt " << dt << " s: error " << error << " K after " << previous << " K";
    }
    previous = error;
  }
}

// The cell-centred finite volumes are second order in space. With the step refined as dx^2 (dt = 0.01 s/mm^2 dx^2)
// the time error shrinks at the same rate, so the RMS error over the heated depth must fall about 4x per halving of
// the cells: observed order within 1.7-2.3.
TEST(ThermalConvergence, GridRefinementIsSecondOrder) {
  double previous = 0.0;
  for (double dx : {4.0, 2.0, 1.0}) {
    const double error = RunColumn(dx, 0.01 * dx * dx, 20.0, 100.0).rms_error_k;
    if (previous > 0.0) {
      const double order = std::log2(previous / error);
      EXPECT_GT(order, 1.7) << "dx " << dx << " mm: error " << error << " K after " << previous << " K";
      EXPECT_LT(order, 2.3) << "dx " << dx << " mm: error " << error << " K after " << previous << " K";
    }
    previous = error;
  }
}

}  // namespace
}  // namespace waam::twin
