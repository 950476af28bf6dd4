// Benchmarks of the planar slicer and the STL reader on a ~1 million facet sphere, 200 mm tall.
#include <filesystem>
#include <vector>

#include <benchmark/benchmark.h>

#include "planner/mesh/generators.h"
#include "analysis/stl_file.h"
#include "planner/mesh/stl_io.h"
#include "planner/slicing/planar_slicer.h"

namespace {

using waam::planner::TriangleMesh;

// Sphere of radius 100 mm with 1000 meridians and 500 latitude bands: 998,000 facets.
const TriangleMesh& BigSphere() {
  static const TriangleMesh mesh = waam::planner::GeneratePart(
      "sphere", {{"radius_mm", {100.0}}, {"segments", {1000.0}}, {"rings", {500.0}}}, "slicing_bench");
  return mesh;
}

// Slices the sphere at 1.5 mm layers (mid-layer heights, 133 planes).
void BM_SlicePlanarSphere1M(benchmark::State& state) {
  const TriangleMesh& mesh = BigSphere();
  std::vector<double> heights;
  for (double z = 0.75; z < 200.0; z += 1.5) heights.push_back(z);
  std::size_t segments = 0;
  for (auto _ : state) {
    waam::planner::SliceReport report;
    auto slices = waam::planner::SlicePlanar(mesh, heights, &report);
    benchmark::DoNotOptimize(slices);
    segments = report.segments;
  }
  const double facets = static_cast<double>(mesh.facets.size());
  state.counters["facets"] = facets;
  state.counters["layers"] = static_cast<double>(heights.size());
  state.counters["segments_per_run"] = static_cast<double>(segments);
  state.counters["facets_per_s"] = benchmark::Counter(facets, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["layers_per_s"] =
      benchmark::Counter(static_cast<double>(heights.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_SlicePlanarSphere1M)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// Reads the same sphere back from a binary STL (parse, weld at 1e-4 mm, report).
void BM_ReadStlBinarySphere1M(benchmark::State& state) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "waam_slicing_bench_sphere.stl";
  waam::analysis::WriteStlBinary(BigSphere(), path);
  for (auto _ : state) {
    waam::planner::MeshReport report;
    auto mesh = waam::analysis::ReadStl(path, 1e-4, &report);
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["facets_per_s"] = benchmark::Counter(static_cast<double>(BigSphere().facets.size()),
                                                      benchmark::Counter::kIsIterationInvariantRate);
  std::filesystem::remove(path);
}
BENCHMARK(BM_ReadStlBinarySphere1M)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
