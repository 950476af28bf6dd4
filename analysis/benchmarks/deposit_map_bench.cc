// Benchmark of the deposit height map's distance bound (twin/cell/deposit_map.h) as the continuous check's torch
// sweep uses it (twin/cell/deposit_sweep.cc): a move whose nozzle lies below the deposit's top cannot be certified by
// the height alone, so each query scans the map's columns within cap + r of the nozzle, with cap = M + 1 mm (M: how
// far the move can bring nozzle and part together). A long travel move below the top has a large M, hence a window of
// (2 (M + 1 + r) + nozzle length)^2 cells per query. Part: a 200 x 150 mm rectangular wall, 40 mm high (20 layers of
// 2 mm, 5 mm beads, 1 mm cells as the check's map); the nozzle (a 30 mm capsule of radius 8 mm, upright) beside the
// wall, 20 mm below its top, 12 mm off its outer face.
#include <cmath>

#include <benchmark/benchmark.h>

#include "twin/cell/deposit_map.h"

namespace {

using waam::twin::DepositMap;

DepositMap Wall() {
  DepositMap map(Eigen::Vector2d(-150.0, -125.0), Eigen::Vector2d(150.0, 125.0), 1.0);
  const Eigen::Vector2d corners[] = {{-100.0, -75.0}, {100.0, -75.0}, {100.0, 75.0}, {-100.0, 75.0}};
  for (int layer = 1; layer <= 20; ++layer) {
    const double z = 2.0 * layer;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d a = corners[k], b = corners[(k + 1) % 4];
      map.Deposit(Eigen::Vector3d(a.x(), a.y(), z), Eigen::Vector3d(b.x(), b.y(), z), 5.0);
    }
  }
  return map;
}

// Arg: M, the move's approach bound, mm (cap = M + 1). Counters: the bound found and the cells in the window.
void BM_DepositDistanceBelowTop(benchmark::State& state) {
  const DepositMap map = Wall();
  const double M = static_cast<double>(state.range(0));
  const double r = 8.0;
  const Eigen::Vector3d a(0.0, -75.0 - 2.5 - 12.0 - r, 20.0), b = a + Eigen::Vector3d(0.0, 0.0, 30.0);
  // The first query rasterises the beads: leave it out of the timing.
  double d = map.Distance(a, b, r, M + 1.0);
  for (auto _ : state) {
    d = map.Distance(a, b, r, M + 1.0);
    benchmark::DoNotOptimize(d);
  }
  const double side = 2.0 * (M + 1.0 + r) + 1.0;
  state.counters["bound_mm"] = d;
  state.counters["window_cells"] = side * side;
}
BENCHMARK(BM_DepositDistanceBelowTop)->Arg(5)->Arg(20)->Arg(50)->Arg(100)->Arg(200)->Unit(benchmark::kMicrosecond);

// The per-sample test of the discrete check at the same place (Penetration: the nozzle as spheres, each against the
// columns under it), for comparison.
void BM_DepositPenetrationBelowTop(benchmark::State& state) {
  const DepositMap map = Wall();
  const double r = 8.0;
  const Eigen::Vector3d a(0.0, -75.0 - 2.5 - 12.0 - r, 20.0), b = a + Eigen::Vector3d(0.0, 0.0, 30.0);
  double p = map.Penetration(a, b, r);
  for (auto _ : state) {
    p = map.Penetration(a, b, r);
    benchmark::DoNotOptimize(p);
  }
  state.counters["penetration_mm"] = p;
}
BENCHMARK(BM_DepositPenetrationBelowTop)->Unit(benchmark::kMicrosecond);

}  // namespace
