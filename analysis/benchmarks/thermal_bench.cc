// The thermal model on one build hour: cells, steps, solver iterations, wall time, peak memory and energy balance
// on 1 and 2 threads (docs/THERMAL.md, "Benchmark").
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <string>

#include <benchmark/benchmark.h>

#include "models/core/parallel.h"
#include "twin/thermal/thermal_simulation.h"

namespace {

using waam::models::ThermalMaterial;

// An aluminium-magnesium filler shaped like ER5356's tables (k 120-150 W/(m K), rho 2640-2380 kg/m^3, cp 900-1180
// J/(kg K), solidus 571 degC, liquidus 638 degC, L 3.9e5 J/kg): a benchmark fixture, not the project's data file.
ThermalMaterial AluminiumLike() {
  ThermalMaterial m;
  m.name = "aluminium_like";
  m.source = "benchmark fixture";
  m.temperature_c = {20.0, 200.0, 400.0, 571.0, 638.0, 900.0};
  m.conductivity_w_mk = {120.0, 135.0, 150.0, 155.0, 90.0, 95.0};
  m.density_kg_m3 = {2640.0, 2610.0, 2570.0, 2530.0, 2390.0, 2350.0};
  m.specific_heat_j_kgk = {900.0, 980.0, 1060.0, 1120.0, 1180.0, 1180.0};
  m.solidus_c = 571.0;
  m.liquidus_c = 638.0;
  m.latent_heat_j_kg = 3.9e5;
  m.emissivity = 0.2;
  return m;
}

// A low-carbon steel shaped like EN 1993-1-2's tables (k 53-27 W/(m K), cp 440-650 J/(kg K) with the 735 degC
// peak smoothed, rho 7850 kg/m^3, solidus 1495 degC, liquidus 1535 degC, L 2.47e5 J/kg): a benchmark fixture.
ThermalMaterial SteelLike() {
  ThermalMaterial m;
  m.name = "steel_like";
  m.source = "benchmark fixture";
  m.temperature_c = {20.0, 400.0, 700.0, 735.0, 800.0, 1200.0, 1495.0, 1535.0, 2000.0};
  m.conductivity_w_mk = {53.3, 42.7, 32.7, 31.5, 27.3, 27.3, 27.3, 27.3, 27.3};
  m.density_kg_m3 = {7850.0, 7850.0, 7850.0, 7850.0, 7850.0, 7850.0, 7850.0, 7850.0, 7850.0};
  m.specific_heat_j_kgk = {440.0, 606.0, 1008.0, 2500.0, 803.0, 650.0, 650.0, 650.0, 650.0};
  m.solidus_c = 1495.0;
  m.liquidus_c = 1535.0;
  m.latent_heat_j_kg = 2.47e5;
  m.emissivity = 0.7;
  return m;
}

double PeakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux reports kB
}

// One build hour: a 200 x 6 mm wall of `layers` 2 mm beads on a 250 x 100 x 15 mm plate, welded back and forth at
// 14 mm/s with 4.5 kW into the metal, 2 s of travel between layers (255 layers: 51 m of bead, 3643 s of arc).
// Arguments: layers, threads.
void BM_ThermalBuildHour(benchmark::State& state) {
  const int layers = static_cast<int>(state.range(0));
  waam::SetThreadCount(static_cast<int>(state.range(1)));
  waam::twin::ThermalSettings settings;
  const bool steel = state.range(2) != 0;
  settings.deposit = steel ? SteelLike() : AluminiumLike();
  settings.substrate = settings.deposit;
  settings.substrate_box_mm = Eigen::AlignedBox3d(Eigen::Vector3d(-125, -50, -15), Eigen::Vector3d(125, 50, 0));
  settings.deposit_box_mm = Eigen::AlignedBox3d(Eigen::Vector3d(-105, -5, 0), Eigen::Vector3d(105, 5, 2.0 * layers));
  settings.table_conductance_w_m2k = 200.0;
  // Fourth argument: the whole model's step (ThermalSettings::whole_step_s, 32 s by default), s; 0 = no such level.
  settings.whole_step_s = static_cast<double>(state.range(3));
  constexpr double kSpeed = 14.0, kHeat = 4500.0, kLength = 200.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    waam::twin::ThermalSimulation sim(settings);
    for (int layer = 0; layer < layers; ++layer) {
      const double z = 2.0 * (layer + 1);
      const double x0 = layer % 2 == 0 ? -kLength / 2 : kLength / 2;
      sim.Weld(Eigen::Vector3d(x0, 0, z), Eigen::Vector3d(-x0, 0, z), 6.0, 2.0, kHeat, kLength / kSpeed);
      sim.Cool(2.0);
    }
    const waam::twin::ThermalStats stats = sim.Stats();
    const waam::twin::EnergyBalance energy = sim.Energy();
    const double top = sim.TemperatureAt(Eigen::Vector3d(0, 0, 2.0 * layers - 1.0));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(seconds);
    state.counters["bead_m"] = layers * kLength / 1000.0;
    state.counters["build_s"] = sim.time_s();
    state.counters["cells"] = static_cast<double>(stats.cells);
    state.counters["active_cells"] = static_cast<double>(stats.active_cells);
    state.counters["steps"] = static_cast<double>(stats.steps);
    state.counters["iterations"] = static_cast<double>(stats.iterations);
    state.counters["coupling_retries"] = static_cast<double>(stats.coupling_retries);
    state.counters["unconverged_cells"] = static_cast<double>(stats.unconverged_cells);
    state.counters["coupling_repairs"] = static_cast<double>(stats.coupling_repairs);
    // Per multirate level: cells x solves (millions), solves, and CG iterations per solve.
    for (std::size_t l = 0; l < stats.level_solves.size(); ++l) {
      std::string level = "L";  // appended: GCC 12's -Wrestrict misfires on "L" + std::string&& (its bug 105329)
      level += std::to_string(l);
      const double solves = static_cast<double>(stats.level_solves[l]);
      state.counters[level + "_Mcell_solves"] = static_cast<double>(stats.level_cell_solves[l]) * 1e-6;
      state.counters[level + "_solves"] = solves;
      state.counters[level + "_it_per_solve"] = solves > 0 ? static_cast<double>(stats.level_iterations[l]) / solves : 0.0;
    }
    state.counters["wall_s"] = seconds;
    state.counters["peak_rss_mb"] = PeakRssMb();
    state.counters["energy_error"] = energy.RelativeError();
    state.counters["top_c"] = top;
  }
  waam::SetThreadCount(0);
}
BENCHMARK(BM_ThermalBuildHour)
    ->ArgNames({"layers", "threads", "steel", "whole_s"})
    ->Args({10, 1, 0, 32})
    ->Args({10, 2, 0, 32})
    ->Args({40, 1, 0, 32})
    ->Args({40, 1, 0, 0})
    ->Args({255, 1, 0, 32})
    ->Args({255, 2, 0, 32})
    ->Args({10, 1, 1, 32})
    ->Args({40, 1, 1, 32})
    ->Args({40, 1, 1, 0})
    ->Args({255, 1, 1, 32})
    ->Args({255, 2, 1, 32})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
