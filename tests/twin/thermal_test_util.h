// Test fixtures for the thermal model: materials built in code, the closed forms it is checked against, and the
// runs shared by the verification tests.
#pragma once

#include <cmath>
#include <numbers>

#include <Eigen/Core>

#include "models/thermal/material.h"
#include "twin/thermal/thermal_simulation.h"

namespace waam::twin::testing {

// A metal with constant properties (no latent heat, no radiation), for the closed forms.
inline models::ThermalMaterial ConstantMaterial(double k_w_mk, double rho_kg_m3, double cp_j_kgk) {
  models::ThermalMaterial m;
  m.name = "constant";
  m.source = "test fixture";
  m.temperature_c = {0.0, 1000.0};
  m.conductivity_w_mk = {k_w_mk, k_w_mk};
  m.density_kg_m3 = {rho_kg_m3, rho_kg_m3};
  m.specific_heat_j_kgk = {cp_j_kgk, cp_j_kgk};
  m.solidus_c = m.liquidus_c = 1e4;
  return m;
}

// A steel-like metal whose conductivity, density and heat capacity all change with temperature, with a latent heat
// over a 50 K mushy zone (a test fixture shaped like low-carbon steel's tables, not data for any real alloy).
inline models::ThermalMaterial VaryingMaterial() {
  models::ThermalMaterial m;
  m.name = "varying";
  m.source = "test fixture";
  m.temperature_c = {20.0, 400.0, 750.0, 900.0, 1450.0, 1500.0, 2000.0};
  m.conductivity_w_mk = {52.0, 42.0, 30.0, 27.0, 30.0, 35.0, 35.0};
  m.density_kg_m3 = {7850.0, 7750.0, 7650.0, 7600.0, 7400.0, 7000.0, 6900.0};
  m.specific_heat_j_kgk = {450.0, 560.0, 900.0, 640.0, 680.0, 780.0, 800.0};
  m.solidus_c = 1450.0;
  m.liquidus_c = 1500.0;
  m.latent_heat_j_kg = 2.7e5;
  m.emissivity = 0.6;
  return m;
}

// ierfc(x) = integral of erfc from x to infinity = exp(-x^2)/sqrt(pi) - x erfc(x) (Carslaw & Jaeger 1959, App. II).
inline double Ierfc(double x) { return std::exp(-x * x) / std::sqrt(std::numbers::pi) - x * std::erfc(x); }

// Temperature rise at depth z (m) of a semi-infinite body under a constant surface flux q (W/m^2) after t seconds:
// dT = (2 q / k) sqrt(alpha t) ierfc(z / (2 sqrt(alpha t))) (Carslaw & Jaeger 1959, §2.9 eq. 6).
inline double SemiInfiniteRise(double q, double k, double alpha, double t, double z) {
  const double root = std::sqrt(alpha * t);
  return 2.0 * q / k * root * Ierfc(z / (2.0 * root));
}

// Quasi-steady rise around a point source Q (W) moving at v (m/s) on the surface of a thick plate (semi-infinite
// body), at xi (m) ahead of the source along its travel and R (m) from it: Q / (2 pi k R) exp(-v (xi + R) / 2 alpha)
// (Rosenthal 1946, eq. 9).
inline double RosenthalRise(double q_w, double k, double alpha, double v, double xi, double r) {
  return q_w / (2.0 * std::numbers::pi * k * r) * std::exp(-v * (xi + r) / (2.0 * alpha));
}

// Settings with every face insulated (no convection, radiation or table) on a constant material, with the uniform
// bead heat source.
inline ThermalSettings InsulatedSettings(const models::ThermalMaterial& material, const Eigen::AlignedBox3d& plate,
                                         const Eigen::AlignedBox3d& deposit, double cell_mm) {
  ThermalSettings s;
  s.deposit = material;
  s.substrate = material;
  s.substrate_box_mm = plate;
  s.deposit_box_mm = deposit;
  s.cell_mm = cell_mm;
  s.convection_w_m2k = 0.0;
  s.emissivity = 0.0;
  s.table_conductance_w_m2k = 0.0;
  // The closed forms' sources are a flux through the top cell and a point source: the bead rule puts the heat into
  // the cells the arc stands on, which is what those tests were built on.
  s.heat_source = HeatSourceShape::kUniformBead;
  return s;
}

// Semi-infinite body: a column one cell wide, `depth_mm` deep, insulated, whose top cell takes `flux_w_m2` through a
// standing arc, for `seconds` in steps of `dt_s`. Returns the max |T - closed form| over the cells within
// 4 sqrt(alpha t) of the top, K, and the surface rise in *rise.
struct ColumnRun {
  double max_error_k = 0.0;
  double rms_error_k = 0.0;
  double surface_rise_k = 0.0;
};
inline ColumnRun RunColumn(double cell_mm, double dt_s, double seconds, double depth_mm) {
  constexpr double k = 40.0, rho = 8000.0, cp = 500.0, flux = 1e6;
  const double alpha = k / (rho * cp);
  const Eigen::AlignedBox3d plate(Eigen::Vector3d(0, 0, -depth_mm), Eigen::Vector3d(cell_mm, cell_mm, 0));
  const Eigen::AlignedBox3d above(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(cell_mm, cell_mm, cell_mm));
  ThermalSettings settings = InsulatedSettings(ConstantMaterial(k, rho, cp), plate, above, cell_mm);
  settings.max_arc_step_s = dt_s;
  settings.far_step_s = 0.0;  // every step solves the whole column: the orders are those of the single-rate scheme
  settings.solver_tolerance_c = 1e-7;
  ThermalSimulation sim(settings);
  const Eigen::Vector3d top(cell_mm / 2, cell_mm / 2, 0.0);
  const double area_m2 = cell_mm * cell_mm * 1e-6;
  sim.Weld(top, top, cell_mm, 0.0, flux * area_m2, seconds);
  ColumnRun run;
  const double reach_mm = 4e3 * std::sqrt(alpha * seconds);
  int cells = 0;
  for (double z = cell_mm / 2; z < reach_mm; z += cell_mm) {
    const double expected = SemiInfiniteRise(flux, k, alpha, seconds, z * 1e-3);
    const double got = sim.TemperatureAt(Eigen::Vector3d(cell_mm / 2, cell_mm / 2, -z)) - settings.initial_c;
    run.max_error_k = std::max(run.max_error_k, std::abs(got - expected));
    run.rms_error_k += (got - expected) * (got - expected);
    ++cells;
    if (cells == 1) run.surface_rise_k = expected;
  }
  run.rms_error_k = std::sqrt(run.rms_error_k / cells);
  return run;
}

// A small build: a 40 mm wall of `layers` beads (4 x 2 mm, 2 kW, 8 mm/s, back and forth, 3 s waits) on a
// 80 x 40 x 6 mm plate of the varying material, cooled 30 s at the end; every loss on (h = 15, emissivity 0.6,
// a 400 W/(m^2 K) table contact).
inline ThermalSettings SmallBuildSettings() {
  ThermalSettings s;
  s.deposit = VaryingMaterial();
  s.substrate = VaryingMaterial();
  s.substrate_box_mm = Eigen::AlignedBox3d(Eigen::Vector3d(-40, -20, -6), Eigen::Vector3d(40, 20, 0));
  s.deposit_box_mm = Eigen::AlignedBox3d(Eigen::Vector3d(-24, -6, 0), Eigen::Vector3d(24, 6, 24));
  s.convection_w_m2k = 15.0;
  s.table_conductance_w_m2k = 400.0;
  s.table_c = 25.0;
  return s;
}
inline void RunSmallBuild(ThermalSimulation& sim, int layers) {
  for (int layer = 0; layer < layers; ++layer) {
    const double z = 2.0 * (layer + 1);
    const double x0 = layer % 2 == 0 ? -20.0 : 20.0;
    sim.Weld(Eigen::Vector3d(x0, 0, z), Eigen::Vector3d(-x0, 0, z), 4.0, 2.0, 2000.0, 40.0 / 8.0);
    sim.Cool(3.0);
  }
  sim.Cool(30.0);
}

}  // namespace waam::twin::testing
