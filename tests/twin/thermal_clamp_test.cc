// Clamps on the plate (ThermalSettings::clamps) against a lumped plate's closed form, and their checks.
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "tests/twin/thermal_test_util.h"

namespace waam::twin {
namespace {

using ::testing::HasSubstr;

// A 40 x 40 x 4 mm plate of a very conductive metal (Biot number G d / k = 2000 x 0.004 / 4000 = 0.002: lumped), at
// 100 degC on a 20 degC table, every face insulated but those the test opens; 2 mm cells, 0.05 s steps.
constexpr double kRhoC = 8000.0 * 500.0;  // J/(m^3 K)
constexpr double kThicknessM = 0.004;
ThermalSettings LumpedPlate() {
  const models::ThermalMaterial metal = testing::ConstantMaterial(4000.0, 8000.0, 500.0);
  ThermalSettings s = testing::InsulatedSettings(metal, Eigen::AlignedBox3d(Eigen::Vector3d(-20, -20, -4),
                                                                             Eigen::Vector3d(20, 20, 0)),
                                                 Eigen::AlignedBox3d(Eigen::Vector3d(-4, -4, 0),
                                                                     Eigen::Vector3d(4, 4, 2)),
                                                 2.0);
  s.initial_c = 100.0;
  s.ambient_c = 20.0;
  s.table_c = 20.0;
  s.max_step_s = 0.05;
  s.far_step_s = 0.0;  // single-rate: every step solves the whole plate
  s.whole_step_s = 0.0;
  return s;
}

// A lumped plate losing through a share `covered` of one face at G: T - T_table = (T0 - T_table) exp(-t / tau),
// tau = rho c V / (G A covered) = rho c d / (G covered) (Incropera & DeWitt, Fundamentals of Heat and Mass Transfer,
// 6th ed., eq. 5.6).
double LumpedC(double g_w_m2k, double covered, double t_s) {
  const double tau = kRhoC * kThicknessM / (g_w_m2k * covered);
  return 20.0 + 80.0 * std::exp(-t_s / tau);
}

double CoolAndRead(const ThermalSettings& s, double seconds, EnergyBalance* energy) {
  ThermalSimulation sim(s);
  sim.Cool(seconds);
  *energy = sim.Energy();
  return sim.TemperatureAt(Eigen::Vector3d(10, 10, -2));
}

// A clamp over the whole top face: the plate decays with tau = 8 s; after one tau the rise is 1/e of the start's,
// within 1 % of the rise (backward Euler at dt = tau / 160 is 0.3 % slow). The heat leaves through the clamps into
// the table.
TEST(ThermalClamps, AWholeTopClampCoolsALumpedPlateAsTheClosedForm) {
  ThermalSettings s = LumpedPlate();
  s.clamps.push_back({Eigen::AlignedBox2d(Eigen::Vector2d(-20, -20), Eigen::Vector2d(20, 20)), 2000.0});
  EnergyBalance e;
  const double t = CoolAndRead(s, 8.0, &e);
  const double expected = LumpedC(2000.0, 1.0, 8.0);
  EXPECT_NEAR(t - 20.0, expected - 20.0, 0.01 * (expected - 20.0)) << "simulated " << t << ", closed form "
                                                                    << expected;
  EXPECT_GT(e.table_j, 0.0);
  EXPECT_NEAR(e.table_j, -e.stored_j, 1e-6 * e.table_j) << "all the heat lost went through the clamp";
  EXPECT_EQ(e.convection_j, 0.0);
}

// A clamp over 13 mm of the plate's 40 mm (its edge cuts a column of cells in half) on the top, 200 W/(m^2 K),
// pressing the plate onto the table beneath it (under_conductance 150) while the rest of the underside is off the
// table: the plate loses through 13/40 of its top and bottom to the table, and by convection (h = 30) through the
// rest of both and its four 40 x 4 mm sides (0.4 of its top's area): G = 350 x 13/40 + 30 (2 x 27/40 + 0.4) = 166
// W/(m^2 K) per top area, tau = 96 s. The patch's conductance is small against the plate's across its width (0.18
// against 47 W/K at k = 4000 W/(m K)): lumped. 0.1 s steps: at 0.5 s the error is 2.7 %, more than backward
// Euler's 0.3 % (likely the CG's stopping rule, 0.01 K a step on a 0.4 K change).
TEST(ThermalClamps, APartialClampLosesInProportionToTheAreaItCovers) {
  ThermalSettings s = LumpedPlate();
  s.convection_w_m2k = 30.0;
  s.max_step_s = 0.1;
  s.clamps.push_back({Eigen::AlignedBox2d(Eigen::Vector2d(-20, -20), Eigen::Vector2d(-7, 20)), 200.0, 150.0});
  const double clamps = 350.0 * 13.0 / 40.0, air = 30.0 * (2.0 * 27.0 / 40.0 + 0.4);
  const double tau = kRhoC * kThicknessM / (clamps + air);
  EnergyBalance e;
  const double t = CoolAndRead(s, tau, &e);
  const double expected = LumpedC(clamps + air, 1.0, tau);
  EXPECT_NEAR(t - 20.0, expected - 20.0, 0.01 * (expected - 20.0)) << "simulated " << t << ", closed form "
                                                                    << expected;
  // The shares of the losses are those of the conductances (the plate is nearly isothermal).
  const double table_share = e.table_j / (e.table_j + e.convection_j);
  EXPECT_NEAR(table_share, clamps / (clamps + air), 0.01);
  EXPECT_LT(std::abs(e.stored_j + e.lost_j), 1e-6 * e.lost_j);
}

// Without clamps the plate's underside on the table is the table's; a clamp with no under_conductance of its own
// keeps it. The same plate with and without a zero-conductance clamp on a table: the same temperatures.
TEST(ThermalClamps, AZeroClampChangesNothing) {
  ThermalSettings s = LumpedPlate();
  s.table_conductance_w_m2k = 800.0;
  EnergyBalance e0, e1;
  const double bare = CoolAndRead(s, 5.0, &e0);
  s.clamps.push_back({Eigen::AlignedBox2d(Eigen::Vector2d(-5, -20), Eigen::Vector2d(5.5, 20)), 0.0});
  const double clamped = CoolAndRead(s, 5.0, &e1);
  EXPECT_NEAR(clamped, bare, 1e-9);
  EXPECT_NEAR(bare - 20.0, LumpedC(800.0, 1.0, 5.0) - 20.0, 0.01 * (bare - 20.0));
}

TEST(ThermalClamps, AClampOffThePlateOrWithANegativeConductanceIsRefused) {
  ThermalSettings s = LumpedPlate();
  s.clamps.push_back({Eigen::AlignedBox2d(Eigen::Vector2d(15, -5), Eigen::Vector2d(25, 5)), 500.0});
  try {
    ThermalSimulation sim(s);
    FAIL() << "a clamp reaching off the plate was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("clamps[0]"));
    EXPECT_THAT(e.what(), HasSubstr("off the plate's top face"));
  }
  s.clamps[0].xy_mm = Eigen::AlignedBox2d(Eigen::Vector2d(10, -5), Eigen::Vector2d(20, 5));
  s.clamps[0].conductance_w_m2k = -1.0;
  try {
    ThermalSimulation sim(s);
    FAIL() << "a negative clamp conductance was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("clamps[0].conductance_w_m2k = -1: must be >= 0"));
  }
}

}  // namespace
}  // namespace waam::twin
