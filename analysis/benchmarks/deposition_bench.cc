// Deposition throughput of the voxel twin: mm of bead and voxels per second, real-time factor and peak memory.
#include <sys/resource.h>

#include <chrono>
#include <cmath>

#include <benchmark/benchmark.h>

#include "models/bead/csw_model.h"
#include "models/fit/model_file.h"

#include "planner/path/tool_path.h"
#include "twin/deposition/bead_deposition.h"

namespace {

using waam::planner::LayerPath;
using waam::planner::PathPoint;
using waam::planner::Plan;

// A square `side` mm filled by one serpentine pass per layer (spacing 0.738 w), raster along x and y alternately.
Plan SerpentineBlock(double side, int layers, double w, double h, double speed) {
  Plan plan;
  const double l = 0.738 * w;
  const int lines = static_cast<int>(std::floor((side - w) / l)) + 1;
  for (int k = 0; k < layers; ++k) {
    LayerPath layer;
    layer.index = k;
    layer.z_mm = (k + 1) * 0.9 * h;
    for (int i = 0; i < lines; ++i) {
      const double across = w / 2 + i * l;
      for (int end = 0; end < 2; ++end) {
        const double along = ((i + end) % 2 == 0) ? w / 2 : side - w / 2;
        PathPoint p;
        p.p_P = k % 2 == 0 ? Eigen::Vector3d(along, across, layer.z_mm) : Eigen::Vector3d(across, along, layer.z_mm);
        p.bead_width_mm = w;
        p.bead_height_mm = h;
        p.speed_mm_s = speed;
        p.weld = !(i == 0 && end == 0);
        layer.points.push_back(p);
      }
    }
    plan.layers.push_back(layer);
  }
  return plan;
}

double PeakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux reports kB
}

void Report(benchmark::State& state, const waam::twin::Depositor& d, double seconds) {
  double build_s = 0.0;
  for (const auto& bead : d.beads()) build_s = std::max(build_s, bead.start_time_s);
  state.counters["bead_m"] = d.weld_length_mm() / 1000.0;
  state.counters["bead_mm_per_s"] = d.weld_length_mm() / seconds;
  state.counters["voxels"] = static_cast<double>(d.grid().occupied());
  state.counters["voxels_per_s"] = d.grid().occupied() / seconds;
  state.counters["volume_error_pct"] =
      100.0 * (d.grid().OccupiedVolume() - d.expected_volume_mm3()) / d.expected_volume_mm3();
  state.counters["grid_mb"] = d.grid().MemoryBytes() / 1048576.0;
  state.counters["peak_rss_mb"] = PeakRssMb();
  state.counters["weld_time_s"] = d.weld_length_mm() / 8.0;
  state.counters["faster_than_real"] = d.weld_length_mm() / 8.0 / seconds;
}

// About one build hour: a 100 x 100 mm block of 24 layers, 6 mm beads at 8 mm/s: 51 m of bead, 106 min of arc
// time. Argument: voxel size in 1/100 mm.
// Deposits `plan` at `voxel_mm` once per iteration, timed by hand (the plan is built outside the timing).
void DepositTimed(benchmark::State& state, const Plan& plan, double voxel_mm) {
  waam::twin::SimulationSettings settings;
  settings.csw = std::make_shared<const waam::models::CswModel>(
      waam::models::CswModel::Load(waam::models::DefaultModelPath("csw")));  // as the scenario loader does
  settings.voxel_mm = voxel_mm;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const waam::twin::Depositor d = waam::twin::DepositPlan(plan, settings, 100.0, nullptr);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(seconds);
    Report(state, d, seconds);
  }
}

void BM_DepositBuildHour(benchmark::State& state) {
  DepositTimed(state, SerpentineBlock(100.0, 24, 6.0, 2.0, 8.0), state.range(0) / 100.0);
}
BENCHMARK(BM_DepositBuildHour)->Arg(100)->Arg(50)->Arg(25)->UseManualTime()->Iterations(1)->Unit(benchmark::kSecond);

// The largest part of the brief: a 200 x 200 mm block 100 mm high (56 layers, about 500 m of bead) at 0.5 mm, for
// the peak memory.
void BM_DepositLargePart(benchmark::State& state) { DepositTimed(state, SerpentineBlock(200.0, 56, 6.0, 2.0, 8.0), 0.5); }
BENCHMARK(BM_DepositLargePart)->UseManualTime()->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
