// Benchmark of `waam check`: samples checked per second (IK + limits + speeds + MuJoCo collisions + torch against
// the deposit) on a build hour of path: 73 layers of a 200 x 150 mm wall = 51,100 mm at 1 mm spacing, about one
// hour of welding at 850 mm/min. With WAAM_CHECK_EXPORT=<dir>, BM_CheckBuildHourUrdfArm also writes the cell's
// collision shapes and the motion's shape poses there for the FCL peer (tools/peers/fcl_check.cc, tools/peers.sh).
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "analysis/cell_files.h"
#include "planner/kinematics/cell_motion.h"
#include "models/core/files.h"
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

// Writes, into `dir`, what the FCL peer needs to check the same motion: check_cell.txt (every collision shape of the
// cell in its geom frame: type, body, sizes in mm, a mesh's triangles as MuJoCo loaded them; the pairs MuJoCo tests;
// the fixed shapes' poses) and check_poses.bin (per reachable sample, per moving shape: the world pose as 12 float32,
// rotation row-major then translation in mm), computed by the cell's forward kinematics at the motion's joints.
void ExportForPeer(const twin::CellModel& cell, const std::vector<planner::CellSample>& motion,
                   const std::filesystem::path& dir) {
  const twin::CellCollisionGeometry g = cell.CollisionGeometry();
  twin::CellState state(cell);
  std::vector<int> moving;
  for (std::size_t i = 0; i < g.shapes.size(); ++i) {
    if (g.lever_mm[i].maxCoeff() > 0.0) moving.push_back(static_cast<int>(i));
  }
  static const char* kType[] = {"plane", "sphere", "capsule", "cylinder", "box", "ellipsoid", "mesh"};
  std::vector<Eigen::Isometry3d> X_WG;
  state.SetJoints(motion.front().q);
  state.ShapePoses(g, &X_WG);
  std::ostringstream txt;
  txt.precision(17);
  txt << "# waam check_bench export: the URDF arm cell of BM_CheckBuildHourUrdfArm (mm)\n";
  txt << "shapes " << g.shapes.size() << "\n";
  for (std::size_t i = 0; i < g.shapes.size(); ++i) {
    const twin::ConvexShape& s = g.shapes[i];
    const bool moves = g.lever_mm[i].maxCoeff() > 0.0;
    txt << "shape " << kType[static_cast<int>(s.type)] << " " << g.body[i] << " " << (moves ? 1 : 0) << " "
        << s.size_mm.transpose() << " " << s.mesh_mm.size() << " " << s.faces.size() << "\n";
    const Eigen::Matrix3d R = X_WG[i].linear();
    const Eigen::Vector3d t = X_WG[i].translation();
    txt << "pose " << R(0, 0) << " " << R(0, 1) << " " << R(0, 2) << " " << R(1, 0) << " " << R(1, 1) << " "
        << R(1, 2) << " " << R(2, 0) << " " << R(2, 1) << " " << R(2, 2) << " " << t.transpose() << "\n";
    for (const Eigen::Vector3d& v : s.mesh_mm) txt << "v " << v.transpose() << "\n";
    for (const std::array<int, 3>& f : s.faces) txt << "f " << f[0] << " " << f[1] << " " << f[2] << "\n";
  }
  txt << "pairs " << g.pairs.size() << "\n";
  for (const std::array<int, 2>& p : g.pairs) txt << p[0] << " " << p[1] << "\n";
  std::string poses;
  std::size_t reachable = 0;
  for (const planner::CellSample& sample : motion) {
    if (!sample.reachable) continue;
    ++reachable;
    state.SetJoints(sample.q);
    state.ShapePoses(g, &X_WG);
    for (int i : moving) {
      float row[12];
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) row[3 * r + c] = static_cast<float>(X_WG[i].linear()(r, c));
        row[9 + r] = static_cast<float>(X_WG[i].translation()[r]);
      }
      poses.append(reinterpret_cast<const char*>(row), sizeof(row));
    }
  }
  txt << "samples " << reachable << " moving";
  for (int i : moving) txt << " " << i;
  txt << "\n";
  EnsureOutputDirectory(dir);
  WriteFileAtomic(dir / "check_cell.txt", txt.str());
  WriteFileAtomic(dir / "check_poses.bin", poses);
}

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
    state.counters["part_mm"] = std::isfinite(report.part_clearance_mm) ? report.part_clearance_mm : 0.0;
    state.counters["part_queries"] = static_cast<double>(report.part_queries);
    benchmark::DoNotOptimize(report.violations.data());
  }
  if (const char* dir = std::getenv("WAAM_CHECK_EXPORT"); dir && *dir && state.range(0) == 0) {
    ExportForPeer(cell, twin::CheckPlan(cell, plan, settings, 100.0, nullptr).motion, dir);
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
