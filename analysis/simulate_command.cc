// `waam simulate` without the planning step: deposit, scan, and write the outputs.
#include "analysis/simulate_command.h"

#include "analysis/scenario.h"
#include "analysis/stl_file.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/core/output_lock.h"
#include "models/core/progress.h"
#include "models/core/run_outputs.h"
#include "planner/geometry/polygon.h"
#include "twin/scanner/surface_mesh.h"
#include "twin/scanner/voxel_surface.h"

namespace waam::analysis {
namespace fs = std::filesystem;

std::vector<std::string> SimulationNotes(const planner::PlanResult& planned) {
  std::vector<std::string> notes;
  char text[512];
  // A layer of beads grows its bead area over the bead spacing (layer_growth_mm, 003 eq. 3.3-3.4); when the slicer
  // steps by a different height, every layer adds the difference and the part outgrows (or falls short of) its target.
  const double layer = planned.layer_height_mm;
  const double grows = planned.layer_growth_mm > 0.0 ? planned.layer_growth_mm : planned.bead_height_mm;
  const std::size_t layers = planned.plan.layers.size();
  if (layer > 0.0 && grows > 0.0 && std::abs(grows - layer) > 0.1 * layer) {
    std::snprintf(text, sizeof(text),
                  "layer height: the layers are planned %.3g mm apart (slicing.layer_height_mm) but a layer of the "
                  "beads laid grows %.3g mm (bead area / bead spacing): over %zu layers the part grows up to %.3g mm "
                  "%s than its target, which the deviation measures include",
                  layer, grows, layers, std::abs(grows - layer) * static_cast<double>(layers),
                  grows > layer ? "taller" : "shorter");
    notes.emplace_back(text);
  }
  // The narrowest sliced wall: 2 x area / perimeter of a region is its thickness for a thin wall (a strip or a ring).
  double wall = std::numeric_limits<double>::infinity();
  for (const planner::LayerPath& l : planned.plan.layers) {
    for (const planner::PolygonWithHoles& region : l.slice) {
      double perimeter = planner::Perimeter(region.outer);
      for (const planner::Ring& hole : region.holes) perimeter += planner::Perimeter(hole);
      if (perimeter > 0.0) wall = std::min(wall, 2.0 * planner::Area(region) / perimeter);
    }
  }
  const double width = planned.bead_width_mm;
  if (std::isfinite(wall) && width > 0.0 && wall < 0.9 * width) {
    std::snprintf(text, sizeof(text),
                  "bead width: the narrowest wall is about %.3g mm thick but the bead is %.3g mm wide "
                  "(path.bead_width_mm): the bead stands up to %.3g mm proud of each side of such a wall",
                  wall, width, 0.5 * (width - wall));
    notes.emplace_back(text);
  }
  return notes;
}

nlohmann::json SimulationToJson(const Scenario& scenario, const planner::PlanResult& planned,
                                const twin::TwinResult& result) {
  const twin::TwinMeasures& m = result.measures;
  const twin::VoidReport& voids = result.voids;
  const twin::SimulationSettings& s = scenario.simulation;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double seconds = std::max(m.deposition_s, 1e-9);
  // Each top-surface measure that does not apply is null, and not_applicable names it with the reason.
  nlohmann::json not_applicable = nlohmann::json::object();
  if (!m.top_surface_not_applicable.empty()) {
    for (const char* key : {"waviness_mm", "ra_mm", "top_height", "boundary_lag_mm"}) {
      not_applicable[key] = m.top_surface_not_applicable;
    }
  }
  return {
      {"scenario", scenario.name},
      {"voxel_mm", m.voxel_mm},
      {"layers", m.layers},
      {"beads", m.beads},
      {"voxels", m.voxels},
      {"weld_length_mm", m.weld_length_mm},
      {"build_time_s", m.build_time_s},
      {"deposited_volume_mm3", m.deposited_volume_mm3},
      {"expected_volume_mm3", m.expected_volume_mm3},
      {"volume_error_pct",
       m.expected_volume_mm3 > 0 ? 100.0 * (m.deposited_volume_mm3 - m.expected_volume_mm3) / m.expected_volume_mm3
                                 : 0.0},
      {"deviation",
       {{"min_mm", result.deviation.min_mm},
        {"max_mm", result.deviation.max_mm},
        {"mean_mm", result.deviation.mean_mm},
        {"rms_mm", result.deviation.rms_mm},
        {"samples", result.deviation.samples}}},
      {"voids",
       {{"count", voids.voids.size()},
        {"volume_mm3", voids.void_volume_mm3},
        {"max_length_mm", voids.void_max_length_mm},
        {"min_volume_mm3", voids.min_volume_mm3},
        {"smaller", {{"count", voids.small_regions}, {"volume_mm3", voids.small_volume_mm3}}}}},
      {"valleys",
       {{"count", voids.valleys.size()},
        {"volume_mm3", voids.valley_volume_mm3},
        {"max_length_mm", voids.valley_max_length_mm}}},
      {"waviness_mm", m.waviness_mm},
      {"ra_mm", m.ra_mm},
      {"top_height", {{"mean_mm", m.top_mean_mm}, {"min_mm", m.top_min_mm}, {"max_mm", m.top_max_mm}}},
      {"boundary_lag_mm", m.boundary_lag.lag_mm},
      {"boundary_lag",
       {{"interior_mean_mm", m.boundary_lag.interior_mean_mm},
        {"boundary_mean_mm", m.boundary_lag.boundary_mean_mm},
        {"interior_columns", m.boundary_lag.interior_columns},
        {"boundary_columns", m.boundary_lag.boundary_columns}}},
      {"not_applicable", not_applicable},
      {"notes", SimulationNotes(planned)},
      {"performance",
       {{"deposition_s", m.deposition_s},
        {"bead_mm_per_s", m.weld_length_mm / seconds},
        {"voxels_per_s", static_cast<double>(m.voxels) / seconds},
        {"grid_memory_mb", static_cast<double>(m.grid_memory_bytes) / 1048576.0},
        {"peak_rss_mb", usage.ru_maxrss / 1024.0}}},
      {"settings",
       {{"blend", s.blend},
        {"blend_radius_mm", s.blend_radius_mm},
        {"blend_time_s", s.blend_time_s},
        {"start_length_mm", s.start_length_mm},
        {"start_height_factor", s.start_height_factor},
        {"start_width_factor", s.start_width_factor},
        {"stop_length_mm", s.stop_length_mm},
        {"stop_height_factor", s.stop_height_factor},
        {"stop_width_factor", s.stop_width_factor},
        {"edge_sag_factor", s.edge_sag_factor},
        {"edge_spread_factor", s.edge_spread_factor},
        {"max_voxels", s.max_voxels}}},
  };
}

twin::TwinResult SimulatePlanned(const Scenario& scenario, const planner::PlanResult& planned,
                                 const SimulateOptions& options) {
  ClaimOutputDirectory(options.out_dir);
  RemoveEarlierSummary(options.out_dir / "simulate.json");
  const twin::SimulationSettings& settings = scenario.simulation;
  CheckVoxelBudget(scenario, planned.plan);
  twin::TwinResult result = [&] {
    Progress progress("deposit", 0, "passes", options.quiet);
    twin::Depositor depositor =
        twin::DepositPlan(planned.plan, settings, scenario.process.rapid_speed_mm_min / 60.0, &progress);
    progress.Finish();
    return twin::MeasureBuild(planned.plan, std::move(depositor), planned.mesh.facets.empty() ? nullptr : &planned.mesh,
                              scenario.path.bead_width_mm);
  }();
  WriteSimulateOutputs(scenario, planned, result, options.out_dir, options.images);
  return result;
}

void CheckVoxelBudget(const Scenario& scenario, const planner::Plan& plan) {
  const twin::SimulationSettings& settings = scenario.simulation;
  double weld_mm3 = 0.0;
  for (const planner::LayerPath& layer : plan.layers) {
    for (std::size_t i = 1; i < layer.points.size(); ++i) {
      const planner::PathPoint& p = layer.points[i];
      if (!p.weld) continue;
      weld_mm3 += 2.0 / 3.0 * p.bead_width_mm * p.bead_height_mm * (p.p_P - layer.points[i - 1].p_P).norm();
    }
  }
  const double estimate = weld_mm3 / std::pow(settings.voxel_mm, 3);
  WAAM_THROW_UNLESS(estimate <= static_cast<double>(settings.max_voxels),
                    scenario.file.string() << ": simulation needs about " << static_cast<long long>(estimate)
                    << " voxels at simulation.voxel_mm = " << settings.voxel_mm << " mm, more than "
                    << "simulation.max_voxels = " << settings.max_voxels << "; use a coarser voxel_mm");
}

planner::TriangleMesh PartSurface(const twin::VoxelGrid& grid, int* factor) {
  constexpr std::size_t kMaxStlFacets = 5000000;
  *factor = 1;
  planner::TriangleMesh surface = twin::ExtractVoxelSurface(grid, kMaxStlFacets);
  while ((surface.facets.empty() || surface.facets.size() > kMaxStlFacets) && *factor < 8 && grid.occupied() > 0) {
    surface = twin::ExtractVoxelSurface(twin::Coarsen(grid, ++*factor), kMaxStlFacets);
  }
  return surface;
}

nlohmann::json WriteSimulateOutputs(const Scenario& scenario, const planner::PlanResult& planned,
                                    const twin::TwinResult& result, const fs::path& out_dir, bool images) {
  ClaimOutputDirectory(out_dir);
  RunOutputs outputs(out_dir / "simulate.json");

  // The part's surface: coplanar voxel faces merged (twin::ExtractVoxelSurface). Past kMaxStlFacets exposed voxel
  // faces or facets it is exported from a coarser copy of the grid (majority of the fine voxels), reported as
  // stl_voxel_mm.
  const auto surface_start = std::chrono::steady_clock::now();
  int factor = 1;
  const planner::TriangleMesh surface = PartSurface(result.depositor.grid(), &factor);
  WriteStlBinary(surface, outputs.Add(out_dir / "part.stl"), "waam simulate: " + scenario.name);
  const double surface_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - surface_start).count();
  const double stl_voxel_mm = factor * result.depositor.grid().voxel_mm();
  WriteSimulationH5(result, outputs.Add(out_dir / "part.h5"));
  if (images) {
    WriteHeightMapPng(result.top, scenario.name, outputs.Add(out_dir / "top_height.png"));
    WriteSectionPng(result, 0, scenario.name, outputs.Add(out_dir / "section_xz.png"));
    WriteSectionPng(result, 1, scenario.name, outputs.Add(out_dir / "section_yz.png"));
    WriteDeviationPng(result, scenario.name, outputs.Add(out_dir / "deviation_map.png"));
  }
  nlohmann::json json = SimulationToJson(scenario, planned, result);
  json["stl_voxel_mm"] = stl_voxel_mm;
  json["stl_facets"] = surface.facets.size();
  json["performance"]["surface_s"] = surface_s;
  CheckInterrupt();  // a Ctrl-C while the outputs were written still ends the run as interrupted (exit 130)
  WriteFileAtomic(out_dir / "simulate.json", JsonText(json) + "\n");
  outputs.Complete();
  return json;
}

}  // namespace waam::analysis
