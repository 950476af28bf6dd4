// One inherent-strain distortion solve of part I (003 Fig. 60: 100 mm diameter), default resolution: time,
// linear-system size (unknowns, stored nonzeros) and peak memory. BM_DistortionSolvePartI: a straight tube of the same
// section and axis length; BM_DistortionSolveBentPartI: scenarios/tubes/part_1.yaml itself (bent, skeleton slicing).
// Arg 0: fe with SimplicialLDLT, 1: reduced mode, 2: fe with ConjugateGradient (incomplete Cholesky, the default).
#include <sys/resource.h>

#include <cmath>
#include <filesystem>

#include <benchmark/benchmark.h>

#include "models/bead/csw_model.h"
#include "models/fit/model_file.h"

#include "analysis/scenario.h"
#include "models/core/numbers.h"
#include "planner/path/tool_path.h"
#include "planner/plan_scenario.h"
#include "planner/scenario/scenario.h"
#include "twin/deposition/bead_deposition.h"
#include "twin/distortion/deposit_history.h"
#include "twin/distortion/distortion.h"

namespace {

// A round tube: one circular pass (2 mm chords) per layer of height h, radius r, bead w, `layers` layers.
waam::planner::Plan Tube(double r, int layers, double w, double h, double speed) {
  waam::planner::Plan plan;
  const int n = static_cast<int>(std::ceil(2.0 * waam::kPi * r / 2.0));
  for (int k = 0; k < layers; ++k) {
    waam::planner::LayerPath layer;
    layer.index = k;
    layer.z_mm = (k + 1) * h;
    for (int i = 0; i <= n; ++i) {
      const double a = 2.0 * waam::kPi * i / n + 0.3 * k;  // the start moves round, as a continuous path's seam would
      waam::planner::PathPoint p;
      p.p_P = Eigen::Vector3d(r * std::cos(a), r * std::sin(a), layer.z_mm);
      p.bead_width_mm = w;
      p.bead_height_mm = h;
      p.speed_mm_s = speed;
      p.weld = i > 0;
      layer.points.push_back(p);
    }
    plan.layers.push_back(layer);
  }
  return plan;
}

// Times ComputeDistortion on the deposit (arg 0: fe with ldlt, 1: reduced, 2: fe with cg) and reports the size of
// the linear system and the peak memory as counters.
void SolveAndReport(benchmark::State& state, const waam::twin::Depositor& depositor,
                    const waam::twin::DepositHistory& history) {
  waam::models::DistortionParams params;
  waam::twin::DistortionOptions options;  // fe, 2 mm elements, 4 groups
  options.mode = state.range(0) == 1 ? waam::models::DistortionMode::kReduced : waam::models::DistortionMode::kFe;
  options.solver = state.range(0) == 0 ? waam::twin::FeSolver::kLdlt : waam::twin::FeSolver::kCg;
  waam::twin::DistortionStats stats;
  for (auto _ : state) {
    const waam::twin::DistortionField field =
        waam::twin::ComputeDistortion(depositor.grid(), history, params, options, &stats);
    benchmark::DoNotOptimize(field.nodes());
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["voxels"] = static_cast<double>(depositor.grid().occupied());
  state.counters["elements"] = static_cast<double>(stats.elements);
  state.counters["dofs"] = static_cast<double>(stats.dofs);
  state.counters["nonzeros"] = static_cast<double>(stats.nonzeros);
  state.counters["solves"] = stats.solves;
  state.counters["solve_s"] = stats.solve_s;
  state.counters["max_u_mm"] = stats.max_displacement_mm;
  state.counters["peak_rss_mb"] = usage.ru_maxrss / 1024.0;
}

void BM_DistortionSolvePartI(benchmark::State& state) {
  // Part I: 100 mm tube; bent axis of radius 150 mm over 90 degrees is about 235 mm long; layers 1-2 mm (Table 16).
  const waam::planner::Plan plan = Tube(50.0, 157, 5.0, 1.5, 8.0);
  waam::twin::SimulationSettings settings;  // default voxel_mm 0.5
  settings.csw = std::make_shared<const waam::models::CswModel>(
      waam::models::CswModel::Load(waam::models::DefaultModelPath("csw")));  // as the scenario loader does
  const waam::twin::Depositor depositor = waam::twin::DepositPlan(plan, settings, 100.0, nullptr);
  const waam::twin::DepositHistory history(plan, depositor, settings, 100.0, 53.3);
  SolveAndReport(state, depositor, history);
}
BENCHMARK(BM_DistortionSolvePartI)->Arg(0)->Arg(1)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond);

void BM_DistortionSolveBentPartI(benchmark::State& state) {
  const waam::analysis::Scenario scenario =
      waam::analysis::LoadScenario(std::filesystem::path(WAAM_SOURCE_DIR) / "scenarios/tubes/part_1.yaml");
  const waam::planner::Plan plan = waam::planner::PlanScenario(scenario, nullptr).plan;
  const double rapid = scenario.process.rapid_speed_mm_min / 60.0;
  const waam::twin::Depositor depositor = waam::twin::DepositPlan(plan, scenario.simulation, rapid, nullptr);
  const waam::twin::DepositHistory history(plan, depositor, scenario.simulation, rapid,
                                           scenario.process.wire_feed_mm_min / 60.0);
  SolveAndReport(state, depositor, history);
}
BENCHMARK(BM_DistortionSolveBentPartI)->Arg(1)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
