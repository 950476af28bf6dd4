// Conservation of energy over a whole small build, the multirate scheme against single-rate stepping, results on
// any thread count, and the checks of the thermal settings.
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "tests/twin/thermal_test_util.h"

namespace waam::twin {
namespace {

using ::testing::HasSubstr;

// Enthalpy of the fixture's metal from `from_c` to `to_c`, J/m^3, by the trapezoid rule on 0.05 K steps of
// ThermalMaterial::EffectiveHeatCapacity (independent of the solver's 1 K tables).
double EnthalpyRise(const models::ThermalMaterial& m, double from_c, double to_c) {
  const int n = std::max(1, static_cast<int>(std::abs(to_c - from_c) / 0.05));
  const double h = (to_c - from_c) / n;
  double sum = 0.5 * (m.EffectiveHeatCapacity(from_c) + m.EffectiveHeatCapacity(to_c));
  for (int i = 1; i < n; ++i) sum += m.EffectiveHeatCapacity(from_c + i * h);
  return sum * h;
}

// Arc heat = heat stored + heat lost. The update moves energy only through faces (each interior flux leaves one cell
// and enters the other), so the balance holds to round-off (~1e-12) whatever the solver's residual; the test asks
// 1 %. The stored heat is also recomputed from the temperature field and the material's own heat capacity: the
// solver's enthalpy tables (1 K nodes, 32 substeps) and the field's floats agree with it to about 1e-4, asked 0.5 %.
TEST(ThermalBalance, ArcHeatEqualsStoredPlusLostOverAWholeBuild) {
  const ThermalSettings settings = testing::SmallBuildSettings();
  ThermalSimulation sim(settings);
  testing::RunSmallBuild(sim, 5);
  const EnergyBalance e = sim.Energy();
  EXPECT_NEAR(e.input_j, 5 * 2000.0 * 5.0, 1.0) << "every weld's heat went into metal";
  EXPECT_LT(e.RelativeError(), 0.01) << "input " << e.input_j << " J, stored " << e.stored_j << " J, lost "
                                     << e.lost_j << " J";
  EXPECT_GT(e.convection_j, 0.0);
  EXPECT_GT(e.radiation_j, 0.0);
  EXPECT_GT(e.table_j, 0.0);
  const TemperatureField field = sim.Field();
  double stored = 0.0;
  for (int k = 0; k < field.size.z(); ++k) {
    for (int j = 0; j < field.size.y(); ++j) {
      for (int i = 0; i < field.size.x(); ++i) {
        const float t = field.temperature_c[i + field.size.x() * (j + field.size.y() * k)];
        if (std::isnan(t)) continue;
        const bool deposit = field.origin_mm.z() + (k + 0.5) * field.cell_mm > 0.0;
        stored += EnthalpyRise(settings.deposit, deposit ? settings.ambient_c : settings.initial_c, t);
      }
    }
  }
  stored *= std::pow(field.cell_mm * 1e-3, 3);
  EXPECT_NEAR(stored, e.stored_j, 0.005 * e.stored_j);
  EXPECT_GT(e.stored_j, 0.3 * e.input_j) << "the part is still warm after 30 s";
}

// Each setting out of its range is refused with its name.
TEST(ThermalSettingsCheck, OutOfRangeSettingsAreRefusedByName) {
  auto refused = [](void (*spoil)(ThermalSettings&), const char* name) {
    ThermalSettings s = testing::SmallBuildSettings();
    spoil(s);
    try {
      ThermalSimulation sim(s);
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(name));
    }
  };
  refused([](ThermalSettings& s) { s.cell_mm = 0.0; }, "cell_mm");
  refused([](ThermalSettings& s) { s.cell_mm = 0.01; }, "cell_mm");
  refused([](ThermalSettings& s) { s.substrate_box_mm = Eigen::AlignedBox3d(); }, "substrate_box_mm");
  refused([](ThermalSettings& s) { s.deposit_box_mm.max().z() = 0.0; }, "deposit_box_mm");
  refused([](ThermalSettings& s) { s.convection_w_m2k = -1.0; }, "convection_w_m2k");
  refused([](ThermalSettings& s) { s.emissivity = 1.5; }, "emissivity");
  refused([](ThermalSettings& s) { s.table_conductance_w_m2k = -5.0; }, "table_conductance_w_m2k");
  refused([](ThermalSettings& s) { s.ambient_c = -300.0; }, "ambient_c");
  refused([](ThermalSettings& s) { s.far_step_s = -1.0; }, "far_step_s");
  refused([](ThermalSettings& s) { s.whole_step_s = -1.0; }, "whole_step_s");
  refused([](ThermalSettings& s) { s.whole_step_s = 32.0, s.whole_radius_mm = 10.0; }, "whole_radius_mm");
  refused([](ThermalSettings& s) { s.arc_radius_mm = 1.0; }, "arc_radius_mm");
  refused([](ThermalSettings& s) { s.solver_tolerance_c = 0.0; }, "solver_tolerance_c");
  refused([](ThermalSettings& s) { s.deposit.temperature_c[2] = 10.0; }, "strictly increasing");
  refused([](ThermalSettings& s) { s.substrate.conductivity_w_mk.pop_back(); }, "function of temperature");
  refused([](ThermalSettings& s) { s.substrate.specific_heat_j_kgk[0] = -1.0; }, "specific_heat_j_kgk");
  ThermalSimulation sim(testing::SmallBuildSettings());
  EXPECT_THROW(sim.Weld(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 4.0, 2.0, -1.0, 1.0), InputError);
  EXPECT_THROW(sim.Cool(-1.0), InputError);
}

}  // namespace
}  // namespace waam::twin
