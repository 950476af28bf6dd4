// `waam thermal replay` and `waam fit thermal` on a one-hour process log at 1 Hz (docs/REPLAY.md, "Benchmark"):
// the replay of the whole log, and a three-parameter fit on its first half, on one thread.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <benchmark/benchmark.h>

#include "analysis/fit_command.h"
#include "analysis/replay_command.h"
#include "analysis/replay_synthetic.h"
#include "models/core/parallel.h"

namespace {
namespace fs = std::filesystem;
using namespace waam::analysis;

// One build hour: a 150 mm mild-steel wall, 30 layers of 2 mm at 6 mm/s and 2 kW, 95 s between layers, on a
// 250 x 100 x 15 mm plate on a table; three thermocouples in the plate. The log is made by the model itself at
// efficiency 0.75, h = 20 W/(m^2 K), table contact 300 W/(m^2 K), with 1 degC of noise.
fs::path HourLog() {
  static const fs::path scenario = [] {
    const fs::path dir = fs::temp_directory_path() / "waam_replay_bench";
    fs::create_directories(dir);
    const fs::path file = dir / "scenario.yaml";
    std::ofstream(file) << "name: replay_hour\n"
                           "part:\n  generator: {type: box, size_mm: [150, 6, 60]}\n"
                           "slicing:\n  layer_height_mm: 2\npath:\n  pattern: zigzag\n  bead_width_mm: 6\n"
                           "process:\n  travel_speed_mm_min: 360\n  wire_feed_mm_min: 3200\n"
                           "  arc: {power_w: 2000, efficiency: 0.84}\n"
                           "thermal:\n  material: mild_steel\n  substrate: {size_mm: [250, 100, 15]}\n"
                           "  cell_mm: 2\n  convection_w_m2k: 10\n  table: {conductance_w_m2k: 100}\n"
                           "replay:\n  log: hour.csv\n  columns: {power_w: power_w}\n"
                           "  bead: {width_mm: 6, height_mm: 2}\n"
                           "  probes:\n    near: {column: T1, at_mm: [0, 10, -2]}\n"
                           "    mid: {column: T2, at_mm: [40, -20, -5]}\n"
                           "    far: {column: T3, at_mm: [100, 35, -10]}\n";
    WallBuildSpec spec;
    spec.layers = 30;
    spec.length_mm = 150.0;
    spec.speed_mm_s = 6.0;
    spec.dwell_s = 95.0;
    spec.tail_s = 95.0;
    const ReplayLog rows = WallBuildLog(spec);
    const std::vector<std::string> columns = {"T1", "T2", "T3"};
    const std::vector<std::vector<double>> blank(3, std::vector<double>(rows.time_s.size(), NAN));
    std::ofstream(dir / "hour.csv") << ReplayLogCsv(rows, columns, blank, 0.0, 1);
    const ReplayModel model = MakeReplayModel(LoadScenario(file), rows);
    ThermalParameters truth = model.parameters;
    truth.efficiency = 0.75;
    truth.convection_w_m2k = 20.0;
    truth.table_conductance_w_m2k = 300.0;
    const ReplaySimulation sim = SimulateReplay(model, truth);
    std::ofstream(dir / "hour.csv") << ReplayLogCsv(rows, columns, sim.probe_c, 1.0, 11);
    return file;
  }();
  return scenario;
}

void BM_ReplayHour(benchmark::State& state) {
  waam::SetThreadCount(1);
  const ReplayModel model = LoadReplayModel(HourLog(), {});
  ReplaySimulation sim;
  for (auto _ : state) sim = SimulateReplay(model, model.parameters);
  state.counters["rows"] = static_cast<double>(model.log.time_s.size());
  state.counters["log_s"] = model.log.time_s.back();
  state.counters["steps"] = static_cast<double>(sim.stats.steps);
  state.counters["cells"] = static_cast<double>(sim.stats.cells);
  state.counters["wall_s"] = sim.wall_s;
}
BENCHMARK(BM_ReplayHour)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

// The three-parameter fit of the hour's first half, on `threads` threads, with a coarse stage on a grid of
// `coarse_mm` (0: none) and the Jacobians on a grid of `jacobian_mm` (0: the scenario's 2 mm grid).
void FitHalfHour(benchmark::State& state, int threads, double coarse_mm, double jacobian_mm) {
  waam::SetThreadCount(threads);
  const fs::path scenario = HourLog();
  FitOptions options;
  options.model = waam::analysis::FitModel::kThermal;
  options.data = scenario;
  options.output = scenario.parent_path() / "fitted.json";
  options.free = {"efficiency", "convection", "contact"};
  options.window = "0:1800";
  options.coarse_cell_mm = coarse_mm;
  options.jacobian_cell_mm = jacobian_mm;
  FitOutcome outcome;
  std::ostringstream out;
  for (auto _ : state) outcome = RunFit(options, out);
  const nlohmann::json& m = outcome.model;
  state.counters["ok"] = outcome.ok ? 1 : 0;
  if (!m.is_object() || !m.contains("fitted")) return;
  state.counters["efficiency"] = m["fitted"]["efficiency"].get<double>();
  state.counters["convection"] = m["fitted"]["convection"].get<double>();
  state.counters["contact"] = m["fitted"]["contact"].get<double>();
  state.counters["replays"] = m["solver"]["replays"].get<double>();
  state.counters["jacobian_grid_replays"] = m["solver"]["coarse_replays"].get<double>();
  state.counters["iterations"] = m["solver"]["iterations"].get<double>();
  state.counters["held_out_rmse_c"] = m["held_out"]["overall"]["rmse_c"].get<double>();
  if (m["coarse"].is_object()) {
    state.counters["coarse_replays"] = m["coarse"]["replays"].get<double>();
    state.counters["coarse_iterations"] = m["coarse"]["iterations"].get<double>();
  }
}

void BM_FitHalfHour(benchmark::State& state) {
  FitHalfHour(state, static_cast<int>(state.range(0)), static_cast<double>(state.range(1)), 0.0);
}
BENCHMARK(BM_FitHalfHour)->Args({1, 4})->Args({1, 0})->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

void BM_FitHalfHourJacobianGrid(benchmark::State& state) {
  FitHalfHour(state, static_cast<int>(state.range(0)), 0.0, static_cast<double>(state.range(1)));
}
// Args: threads, the Jacobians' grid in mm (--jacobian-cell; the residuals on the scenario's 2 mm grid).
BENCHMARK(BM_FitHalfHourJacobianGrid)->Args({1, 3})->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
