// Benchmark of `waam check`: samples checked per second (IK + limits + speeds + MuJoCo collisions + torch against
// the deposit) on a build hour of path: 73 layers of a 200 x 150 mm wall = 51,100 mm at 1 mm spacing, about one
// hour of welding at 850 mm/min.
#include <filesystem>

#include <benchmark/benchmark.h>

#include "analysis/cell_files.h"
#include "planner/kinematics/cell_motion.h"
#include "tests/twin/test_plans.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"

namespace {

using namespace waam;

planner::Plan BuildHour() { return twin::testing::RectangleWall(73, 200.0, 150.0, 2.0, 850.0 / 60.0); }

// Full check: motion (positioner angles, IK, time stamps) and every check.
void BM_CheckBuildHour(benchmark::State& state) {
  const planner::Plan plan = BuildHour();
  const twin::CellSettings settings;
  const twin::CellModel cell = waam::analysis::LoadCell(settings);
  std::size_t samples = 0;
  bool ok = true;
  for (auto _ : state) {
    const twin::CheckReport report = twin::CheckPlan(cell, plan, settings, 100.0, nullptr);
    samples = report.samples;
    ok = report.ok;
    benchmark::DoNotOptimize(report.violations.data());
  }
  state.counters["samples"] = static_cast<double>(samples);
  state.counters["ok"] = ok ? 1.0 : 0.0;
  state.counters["samples_per_s"] =
      benchmark::Counter(static_cast<double>(samples) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CheckBuildHour)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// The same build hour on an arm read from URDF with mesh collision geometry: the KUKA KR 16-2 class arm of
// scenarios/cell/robots/waam_kr16_support (binary STL meshes on three links, primitives on the others).
// Argument 0: discrete mode (MuJoCo at the samples), 1: continuous (conservative advancement between samples).
void BM_CheckBuildHourUrdfArm(benchmark::State& state) {
  const planner::Plan plan = BuildHour();
  twin::CellSettings settings;
  settings.check_mode = state.range(0) == 1 ? twin::CheckMode::kContinuous : twin::CheckMode::kDiscrete;
  const std::filesystem::path robots = std::filesystem::path(WAAM_SOURCE_DIR) / "scenarios" / "cell" / "robots";
  settings.robot_urdf = robots / "waam_kr16_support" / "urdf" / "kr16_2.urdf";
  settings.robot_package_paths = {robots};
  settings.positioner_base_mm = {1150.0, 0.0, 0.0};
  const twin::CellModel cell = waam::analysis::LoadCell(settings);
  std::size_t samples = 0, queries = 0;
  bool ok = true;
  double clearance = 0.0;
  for (auto _ : state) {
    const twin::CheckReport report = twin::CheckPlan(cell, plan, settings, 100.0, nullptr);
    samples = report.samples;
    ok = report.ok;
    queries = report.distance_queries;
    clearance = report.certified_clearance_mm;
    state.counters["poses"] = static_cast<double>(report.poses);
    state.counters["gjk"] = static_cast<double>(report.gjk_queries);
    state.counters["refine"] = static_cast<double>(report.refinements);
    state.counters["min_mm"] = report.sweep_min_distance_mm;
    benchmark::DoNotOptimize(report.violations.data());
  }
  state.counters["samples"] = static_cast<double>(samples);
  state.counters["ok"] = ok ? 1.0 : 0.0;
  state.counters["closed_form"] = cell.closed_form() ? 1.0 : 0.0;
  state.counters["queries"] = static_cast<double>(queries);
  state.counters["clearance_mm"] = clearance;
  state.counters["samples_per_s"] =
      benchmark::Counter(static_cast<double>(samples) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CheckBuildHourUrdfArm)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// The kinematics alone: positioner angles and closed-form IK with branch continuity for every sample.
void BM_MotionBuildHour(benchmark::State& state) {
  const planner::Plan plan = BuildHour();
  const twin::CellModel cell = waam::analysis::LoadCell(twin::CellSettings{});
  const planner::CellKinematics kin = twin::PartKinematics(cell, twin::CellSettings{});
  planner::MotionOptions options;
  std::size_t samples = 0;
  for (auto _ : state) {
    const std::vector<planner::CellSample> motion = planner::PlanCellMotion(kin, plan, options, {});
    samples = motion.size();
    benchmark::DoNotOptimize(motion.data());
  }
  state.counters["samples"] = static_cast<double>(samples);
  state.counters["samples_per_s"] =
      benchmark::Counter(static_cast<double>(samples) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MotionBuildHour)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
