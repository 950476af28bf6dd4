// The table as a body under the plate (ThermalSettings::table_thickness_mm) against two lumped slabs' closed form.
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "tests/twin/thermal_test_util.h"

namespace waam::twin {
namespace {

using ::testing::HasSubstr;

// A 40 x 40 x 4 mm plate at 100 degC on a table body of the same footprint, 4 mm thick, at 20 degC, of a very
// conductive metal (Biot number h d / k = 2000 x 0.004 / 4000 = 0.002: both lumped), every outer face insulated;
// 2 mm cells, 0.02 s steps, single-rate.
constexpr double kRhoC = 8000.0 * 500.0;  // J/(m^3 K)
ThermalSettings PlateOnTableBody(double contact_w_m2k) {
  const models::ThermalMaterial metal = testing::ConstantMaterial(4000.0, 8000.0, 500.0);
  ThermalSettings s = testing::InsulatedSettings(metal, Eigen::AlignedBox3d(Eigen::Vector3d(-20, -20, -4),
                                                                             Eigen::Vector3d(20, 20, 0)),
                                                 Eigen::AlignedBox3d(Eigen::Vector3d(-4, -4, 0),
                                                                     Eigen::Vector3d(4, 4, 2)),
                                                 2.0);
  s.initial_c = 100.0;
  s.ambient_c = 20.0;
  s.table_c = 20.0;
  s.table_conductance_w_m2k = contact_w_m2k;
  s.table_thickness_mm = 4.0;
  s.table_margin_mm = 0.0;
  s.max_step_s = 0.02;
  s.far_step_s = 0.0;
  s.whole_step_s = 0.0;
  return s;
}

// Two lumped slabs of capacities C1 = C2 = rho c d per area joined by a contact h: their difference decays as
// exp(-t / tau), tau = (C1 C2 / (C1 + C2)) / h = rho c d / (2 h) = 4 s, about their mean, 60 degC, which the
// exchange keeps (Incropera & DeWitt, 6th ed., eq. 5.6 for each slab with the other's temperature as its
// surroundings). After one tau the plate reads 60 + 40 / e and the table 60 - 40 / e, within 1 % of the difference
// (backward Euler at dt = tau / 200; the half cells' resistance is 0.05 % of the contact's). No heat leaves the
// model.
TEST(ThermalTableBody, ThePlateAndTheTableExchangeHeatAsTwoLumpedSlabs) {
  const ThermalSettings s = PlateOnTableBody(2000.0);
  const double tau = kRhoC * 0.004 / (2.0 * 2000.0);
  ThermalSimulation sim(s);
  sim.Cool(tau);
  const double plate = sim.TemperatureAt(Eigen::Vector3d(10, 10, -2));
  const double table = sim.TemperatureAt(Eigen::Vector3d(10, 10, -6));
  const double half_difference = 40.0 / std::exp(1.0);
  EXPECT_NEAR(plate - 60.0, half_difference, 0.01 * half_difference) << "plate " << plate;
  EXPECT_NEAR(60.0 - table, half_difference, 0.01 * half_difference) << "table " << table;
  const EnergyBalance e = sim.Energy();
  EXPECT_EQ(e.lost_j, 0.0);
  EXPECT_LT(std::abs(e.stored_j), 1e-9 * kRhoC * 40e-3 * 40e-3 * 4e-3 * 80.0)
      << "the heat the plate gave is in the table (stored " << e.stored_j << " J)";
}

// A table margin that is not a multiple of the cell (3 mm on 2 mm cells) leaves the plate's cells where they are:
// its edges are cell faces, so its metal spans x = -20 ... 20 mm exactly (a grid started at the table's corner,
// x = -23 mm, put cell centres on the plate's edges and made it 42 mm wide).
TEST(ThermalTableBody, TheMarginDoesNotMoveThePlatesEdges) {
  ThermalSettings s = PlateOnTableBody(2000.0);
  s.table_margin_mm = 3.0;
  const TemperatureField f = ThermalSimulation(s).Field();
  const int j = static_cast<int>(std::floor((1.0 - f.origin_mm.y()) / f.cell_mm));
  const int k = static_cast<int>(std::floor((-1.0 - f.origin_mm.z()) / f.cell_mm));  // the plate's top row
  int first = -1, last = -1;
  for (int i = 0; i < f.size.x(); ++i) {
    const std::size_t c = static_cast<std::size_t>(i + f.size.x() * (j + f.size.y() * k));
    if (!std::isfinite(f.temperature_c[c])) continue;
    if (first < 0) first = i;
    last = i;
  }
  ASSERT_GE(first, 0) << "no metal in the plate's top row";
  EXPECT_NEAR(f.origin_mm.x() + first * f.cell_mm, -20.0, 1e-9);
  EXPECT_NEAR(f.origin_mm.x() + (last + 1) * f.cell_mm, 20.0, 1e-9);
}

// Without a contact the body is refused; a negative thickness or margin likewise.
TEST(ThermalTableBody, ABodyWithoutContactOrANegativeSizeIsRefused) {
  ThermalSettings s = PlateOnTableBody(0.0);
  try {
    ThermalSimulation sim(s);
    FAIL() << "a table body without a contact was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("table_conductance_w_m2k = 0: must be > 0 with a table body"));
  }
  s = PlateOnTableBody(1000.0);
  s.table_thickness_mm = -1.0;
  EXPECT_THROW(ThermalSimulation{s}, InputError);
  s.table_thickness_mm = 4.0;
  s.table_margin_mm = -1.0;
  try {
    ThermalSimulation sim(s);
    FAIL() << "a negative table margin was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("table_margin_mm = -1: must be >= 0"));
  }
}

}  // namespace
}  // namespace waam::twin
