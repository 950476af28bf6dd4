// Inner loops under the planner and the cell check: polygon offsetting (Clipper) on a plate with holes and the
// closed-form OPW inverse kinematics of the ARC Mate 100iC/12 per path point.
#include <cmath>
#include <numbers>
#include <vector>

#include <benchmark/benchmark.h>

#include "analysis/benchmarks/bench_shapes.h"
#include "planner/geometry/polygon.h"
#include "planner/kinematics/opw_arm.h"

namespace {

using waam::planner::PolygonWithHoles;

// One inward offset of the plate (round joins), the step of every contour ring: offsets per second.
void BM_OffsetPlateInward(benchmark::State& state) {
  const std::vector<PolygonWithHoles> plate = {waam::bench::HoledPlate(96)};
  const double delta_mm = -static_cast<double>(state.range(0));
  std::size_t regions = 0;
  for (auto _ : state) {
    const auto offset = waam::planner::OffsetRegions(plate, delta_mm);
    regions = offset.size();
    benchmark::DoNotOptimize(offset.data());
  }
  state.counters["regions"] = static_cast<double>(regions);
  state.counters["offsets_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_OffsetPlateInward)->Arg(3)->Arg(12)->Unit(benchmark::kMicrosecond);

// Closed-form IK (all eight branches) plus the nearest-branch pick, for flange poses along a 400 mm line in front of
// the arm with the torch pointing down: the per-point cost of `waam check` before collisions.
void BM_OpwIkPerPoint(benchmark::State& state) {
  const waam::planner::OpwArm arm = waam::planner::OpwArm::ArcMate100iC12();
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < 400; ++i) {
    Eigen::Isometry3d X_RF = Eigen::Isometry3d::Identity();
    X_RF.linear() = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    X_RF.translation() = Eigen::Vector3d(900.0, -200.0 + i, 300.0);
    poses.push_back(X_RF);
  }
  waam::planner::Joints6 seed = waam::planner::Joints6::Zero();
  std::size_t solved = 0;
  for (auto _ : state) {
    solved = 0;
    for (const Eigen::Isometry3d& X_RF : poses) {
      const auto solutions = waam::planner::SolveIk(arm, X_RF, &seed);
      const int pick = waam::planner::PickNearest(arm, solutions, &seed);
      solved += pick >= 0 ? 1 : 0;
      benchmark::DoNotOptimize(pick);
    }
  }
  state.counters["reachable_share"] = static_cast<double>(solved) / static_cast<double>(poses.size());
  state.counters["points_per_s"] = benchmark::Counter(static_cast<double>(poses.size()),
                                                      benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_OpwIkPerPoint)->Unit(benchmark::kMicrosecond);

}  // namespace
