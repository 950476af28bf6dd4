// Writing part.stl: the merged voxel surface against one facet pair per exposed voxel face, on simulated scenarios.
#include <ctime>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "analysis/scenario.h"
#include "analysis/scenario_plan.h"
#include "analysis/simulate_command.h"
#include "analysis/stl_file.h"
#include "twin/scanner/surface_mesh.h"
#include "twin/scanner/voxel_surface.h"
#include "twin/simulation.h"

namespace {

namespace fs = std::filesystem;
using waam::planner::TriangleMesh;
using waam::twin::VoxelGrid;

// The deposited grid of a scenario (relative to the source tree), simulated once per process.
const VoxelGrid& Grid(const std::string& scenario_file) {
  static std::map<std::string, std::unique_ptr<waam::twin::TwinResult>> cache;
  auto& slot = cache[scenario_file];
  if (!slot) {
    const waam::analysis::Scenario scenario =
        waam::analysis::LoadScenario(fs::path(WAAM_SOURCE_DIR) / "scenarios" / scenario_file);
    const waam::planner::PlanResult planned = waam::analysis::PlanScenarioOrProgram(scenario, nullptr);
    slot = std::make_unique<waam::twin::TwinResult>(waam::twin::MeasureBuild(
        planned.plan,
        waam::twin::DepositPlan(planned.plan, scenario.simulation, scenario.process.rapid_speed_mm_min / 60.0,
                                nullptr),
        planned.mesh.facets.empty() ? nullptr : &planned.mesh, scenario.path.bead_width_mm));
  }
  return slot->depositor.grid();
}

// One facet pair per voxel face (demo only: past 10 M faces it exceeds the STL writer's limit) between metal and air (faces on the substrate excluded), vertices not shared: the
// part.stl the merged surface replaces.
TriangleMesh PerFaceMesh(const VoxelGrid& grid) {
  TriangleMesh mesh;
  const double s = grid.voxel_mm();
  grid.ForEach([&](const waam::twin::VoxelIndex& v, const waam::twin::VoxelData&) {
    for (int d = 0; d < 6; ++d) {
      const int axis = d / 2, sign = d % 2 == 0 ? 1 : -1;
      waam::twin::VoxelIndex n = v;
      n[axis] += sign;
      if (grid.Solid(n)) continue;
      const Eigen::Vector3d o = v.cast<double>() * s;
      Eigen::Vector3d e0 = Eigen::Vector3d::Zero(), e1 = Eigen::Vector3d::Zero(), base = o;
      e0[(axis + 1) % 3] = s;
      e1[(axis + 2) % 3] = s;
      if (sign > 0) base[axis] += s;
      if (sign < 0) std::swap(e0, e1);  // counter-clockwise seen from outside
      const int i = static_cast<int>(mesh.vertices.size());
      mesh.vertices.insert(mesh.vertices.end(), {base, base + e0, base + e0 + e1, base + e1});
      mesh.facets.push_back({i, i + 1, i + 2});
      mesh.facets.push_back({i, i + 2, i + 3});
    }
  });
  return mesh;
}

const fs::path& OutFile() {
  static const fs::path path = fs::temp_directory_path() / "waam_surface_bench.stl";
  return path;
}

void Report(benchmark::State& state, const TriangleMesh& mesh) {
  // Facets by the way they face: up (tops of beads and of the steps between them), down, and sideways (walls and
  // the risers of the steps).
  double up = 0, down = 0;
  for (const auto& f : mesh.facets) {
    const double nz = (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]).z();
    up += nz > 0 ? 1 : 0;
    down += nz < 0 ? 1 : 0;
  }
  state.counters["facets_up"] = up;
  state.counters["facets_down"] = down;
  state.counters["facets_side"] = static_cast<double>(mesh.facets.size()) - up - down;
  state.counters["vertices"] = static_cast<double>(mesh.vertices.size());
  state.counters["facets"] = static_cast<double>(mesh.facets.size());
  state.counters["bytes"] = static_cast<double>(fs::file_size(OutFile()));
}

// Build the per-face mesh and write it.
void BM_PerFaceStl(benchmark::State& state, const std::string& scenario) {
  const VoxelGrid& grid = Grid(scenario);
  TriangleMesh mesh;
  for (auto _ : state) {
    mesh = PerFaceMesh(grid);
    waam::analysis::WriteStlBinary(mesh, OutFile());
  }
  Report(state, mesh);
}

// Extract the merged surface (analysis::PartSurface) and write it, as `waam simulate` does.
void BM_VoxelSurfaceStl(benchmark::State& state, const std::string& scenario) {
  const VoxelGrid& grid = Grid(scenario);
  TriangleMesh mesh;
  int factor = 1;
  for (auto _ : state) {
    mesh = waam::analysis::PartSurface(grid, &factor);
    waam::analysis::WriteStlBinary(mesh, OutFile());
  }
  state.counters["voxel_mm"] = factor * grid.voxel_mm();
  Report(state, mesh);
}

// The steps of PartSurface on one grid, timed apart (CPU seconds as counters): the attempt at the grid's own voxel
// size (stopped at the facet cap), the coarsening, the extraction from the coarse grid and the write.
void BM_SurfaceSteps(benchmark::State& state, const std::string& scenario) {
  const VoxelGrid& grid = Grid(scenario);
  auto cpu = [] { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; };
  for (auto _ : state) {
    double t0 = cpu();
    TriangleMesh mesh = waam::twin::ExtractVoxelSurface(grid, 5000000);
    double t1 = cpu();
    state.counters["fine_s"] = t1 - t0;
    state.counters["fine_facets"] = static_cast<double>(mesh.facets.size());
    if (!mesh.facets.empty()) continue;
    const VoxelGrid coarse = waam::twin::Coarsen(grid, 2);
    double t2 = cpu();
    state.counters["coarsen_s"] = t2 - t1;
    mesh = waam::twin::ExtractVoxelSurface(coarse, 5000000);
    double t3 = cpu();
    state.counters["coarse_extract_s"] = t3 - t2;
    waam::analysis::WriteStlBinary(mesh, OutFile());
    state.counters["write_s"] = cpu() - t3;
  }
}

// The part.stl `waam simulate` wrote before the merged surface: the marching-tetrahedra surface
// (twin::ExtractSurface), from a grid coarsened until about ten facets per exposed face came under 5 M.
void BM_TetraStl(benchmark::State& state, const std::string& scenario) {
  const VoxelGrid& grid = Grid(scenario);
  TriangleMesh mesh;
  int factor = 1;
  for (auto _ : state) {
    const double faces = static_cast<double>(waam::twin::ExposedFaces(grid));
    factor = 1;
    while (10.0 * faces / (factor * factor) > 5.0e6 && factor < 8) ++factor;
    mesh = factor == 1 ? waam::twin::ExtractSurface(grid) : waam::twin::ExtractSurface(waam::twin::Coarsen(grid, factor));
    waam::analysis::WriteStlBinary(mesh, OutFile());
  }
  state.counters["voxel_mm"] = factor * grid.voxel_mm();
  Report(state, mesh);
}

BENCHMARK_CAPTURE(BM_TetraStl, demo, std::string("planar_demo.yaml"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PerFaceStl, demo, std::string("planar_demo.yaml"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_VoxelSurfaceStl, demo, std::string("planar_demo.yaml"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_TetraStl, large_block, std::string("twin/large_block.yaml"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_SurfaceSteps, large_block, std::string("twin/large_block.yaml"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_VoxelSurfaceStl, large_block, std::string("twin/large_block.yaml"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
