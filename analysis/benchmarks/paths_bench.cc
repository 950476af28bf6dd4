// Speed of the layer patterns on a 200 x 150 mm plate with three holes (w = 6 mm): layers planned per second.
#include <string>

#include <benchmark/benchmark.h>

#include "analysis/benchmarks/bench_shapes.h"
#include "planner/path/layer_pattern.h"

namespace {

using waam::planner::PolygonWithHoles;

void PlanPlate(benchmark::State& state, const std::string& pattern) {
  const PolygonWithHoles plate = waam::bench::HoledPlate(24);
  waam::planner::PatternOptions options;
  options.pattern = waam::ParseEnum<waam::planner::Pattern>(pattern).value();
  options.bead_width_mm = 6.0;
  std::size_t moves = 0;
  for (auto _ : state) {
    options.layer_index = static_cast<int>(state.iterations() % 16);
    const auto path = waam::planner::PlanLayerPattern({plate}, options);
    moves = path.size();
    benchmark::DoNotOptimize(path.data());
  }
  state.counters["layers/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["moves/layer"] = static_cast<double>(moves);
}

BENCHMARK_CAPTURE(PlanPlate, continuous, std::string("continuous"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(PlanPlate, hybrid, std::string("hybrid"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(PlanPlate, contour, std::string("contour"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(PlanPlate, zigzag, std::string("zigzag"))->Unit(benchmark::kMillisecond);

}  // namespace
