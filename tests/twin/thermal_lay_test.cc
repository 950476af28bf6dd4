// Metal laid at the ambient temperature without solving (ThermalSimulation::LayAtAmbient) against the same metal
// laid by zero-heat welds.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "models/core/error.h"
#include "tests/twin/thermal_test_util.h"

namespace waam::twin {
namespace {

// A 40 x 4 x 4 mm wall (two layers of 2 mm cells) in SmallBuildSettings' deposit box.
const Eigen::AlignedBox3d kWall(Eigen::Vector3d(-20, -2, 0), Eigen::Vector3d(20, 2, 4));
const std::vector<Eigen::Vector3d> kLayProbes = {{0, 0, 1}, {10, 0, 3}, {0, 10, -1}, {-10, 0, -3}, {0, 0, 5}};

// A heated pass along the wall's top and some cooling; the probes' temperatures after it.
std::vector<double> HeatAndCool(ThermalSimulation& sim) {
  sim.Weld(Eigen::Vector3d(-20, 0, 6), Eigen::Vector3d(20, 0, 6), 4.0, 2.0, 2000.0, 5.0);
  sim.Cool(10.0);
  std::vector<double> t;
  for (const Eigen::Vector3d& p : kLayProbes) t.push_back(sim.TemperatureAt(p));
  return t;
}

// Laying the wall at once gives the cells and, after a heated pass, the temperatures that laying it by zero-heat
// welds over a nanosecond gives (the nanosecond's micro steps move no heat), single-rate and multirate.
TEST(ThermalLay, LayingAtOnceMatchesZeroHeatWelds) {
  for (const double far_step_s : {0.0, 8.0}) {
    ThermalSettings settings = testing::SmallBuildSettings();
    settings.far_step_s = far_step_s;
    settings.initial_c = settings.ambient_c;  // the plate at the temperature the laid cells take
    ThermalSimulation laid(settings), welded(settings);
    const std::size_t plate = laid.Stats().active_cells;
    EXPECT_EQ(laid.LayAtAmbient(kWall), 20u * 2u * 2u) << "the wall's 20 x 2 x 2 cells";
    EXPECT_EQ(laid.LayAtAmbient(kWall), 0u) << "cells already on stay as they are";
    for (const double top : {2.0, 4.0}) {
      welded.Weld(Eigen::Vector3d(-20, 0, top), Eigen::Vector3d(20, 0, top), 4.0, 2.0, 0.0, 1e-9);
    }
    EXPECT_EQ(laid.Stats().active_cells, plate + 80u);
    EXPECT_EQ(welded.Stats().active_cells, laid.Stats().active_cells);
    EXPECT_DOUBLE_EQ(laid.TemperatureAt(Eigen::Vector3d(0, 0, 3)), settings.ambient_c);
    const std::vector<double> a = HeatAndCool(laid), b = HeatAndCool(welded);
    for (std::size_t p = 0; p < kLayProbes.size(); ++p) {
      EXPECT_GT(a[p], settings.ambient_c + 1.0) << "probe " << p << " is heated (far_step_s " << far_step_s << ")";
      // Within the CG's tolerance (0.01 K): the cells are the same, only their order in the solver differs.
      EXPECT_NEAR(a[p], b[p], 0.02) << "probe " << p << " (far_step_s " << far_step_s << ")";
    }
    EXPECT_LT(laid.Energy().RelativeError(), 1e-6);
  }
}

// Only deposit cells switch on (never plate or empty cells outside the deposit box); an empty box lays nothing; a
// box that is not finite is refused.
TEST(ThermalLay, LaysOnlyDepositCellsAndRefusesABoxThatIsNotFinite) {
  const ThermalSettings settings = testing::SmallBuildSettings();
  ThermalSimulation sim(settings);
  const std::size_t plate = sim.Stats().active_cells;
  // The box reaches through the plate and beyond the deposit box (x to +-30 mm, y to +-8 mm, z to 30 mm): only the
  // deposit box's 24 x 6 x 12 cells switch on.
  const Eigen::AlignedBox3d big(Eigen::Vector3d(-30, -8, -6), Eigen::Vector3d(30, 8, 30));
  EXPECT_EQ(sim.LayAtAmbient(big), 24u * 6u * 12u);
  EXPECT_EQ(sim.Stats().active_cells, plate + 24u * 6u * 12u);
  EXPECT_EQ(sim.LayAtAmbient(Eigen::AlignedBox3d()), 0u);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  try {
    sim.LayAtAmbient(Eigen::AlignedBox3d(Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d(1, 1, 1)));
    ADD_FAILURE() << "a box with a NaN corner was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace waam::twin
