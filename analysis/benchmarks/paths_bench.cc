// Speed of the layer patterns on a 200 x 150 mm plate with three holes (w = 6 mm): layers planned per second.
#include <cmath>
#include <numbers>
#include <string>

#include <benchmark/benchmark.h>

#include "planner/path/layer_pattern.h"

namespace {

using waam::planner::PolygonWithHoles;
using waam::planner::Ring;

Ring Rect(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// The same plate as tests/planner/test_shapes.h: a square hole, a 22 mm round bore (24-gon) and a tilted slot.
PolygonWithHoles Plate() {
  PolygonWithHoles plate{Rect(0, 0, 200, 150), {}};
  plate.holes.push_back(Rect(30, 30, 70, 70));
  Ring bore;
  for (int k = 0; k < 24; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 24;
    bore.emplace_back(140 + 22 * std::cos(a), 90 + 22 * std::sin(a));
  }
  plate.holes.push_back(bore);
  plate.holes.push_back({{40, 105}, {95, 115}, {92, 130}, {37, 120}});
  return plate;
}

void PlanPlate(benchmark::State& state, const std::string& pattern) {
  const PolygonWithHoles plate = Plate();
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
