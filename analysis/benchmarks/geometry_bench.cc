// Inner loops under the planner and the cell check: polygon offsetting (Clipper) on a plate with holes and the
// closed-form OPW inverse kinematics of the ARC Mate 100iC/12 per path point.
#include <cmath>
#include <numbers>
#include <vector>

#include <benchmark/benchmark.h>

#include "planner/geometry/polygon.h"
#include "planner/kinematics/opw_arm.h"

namespace {

using waam::planner::PolygonWithHoles;
using waam::planner::Ring;

Ring Rect(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// A 200 x 150 mm plate with a square hole, a 22 mm round bore (96-gon) and a tilted slot.
PolygonWithHoles Plate() {
  PolygonWithHoles plate{Rect(0, 0, 200, 150), {}};
  plate.holes.push_back(Rect(30, 30, 70, 70));
  Ring bore;
  for (int k = 0; k < 96; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 96;
    bore.emplace_back(140 + 22 * std::cos(a), 90 + 22 * std::sin(a));
  }
  plate.holes.push_back(bore);
  plate.holes.push_back({{40, 105}, {95, 115}, {92, 130}, {37, 120}});
  return plate;
}

// One inward offset of the plate (round joins), the step of every contour ring: offsets per second.
void BM_OffsetPlateInward(benchmark::State& state) {
  const std::vector<PolygonWithHoles> plate = {Plate()};
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
