// `waam plan`: planning plus its outputs (JSON summary, HDF5 points, per-layer pictures).
#include "analysis/plan_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>
#include <string>

#include "analysis/import_command.h"
#include "analysis/scenario_plan.h"
#include "analysis/plan_timeline.h"
#include "analysis/scenario.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/core/output_lock.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "models/core/run_outputs.h"
#include "planner/path/coverage.h"
#include "planner/scenario/scenario.h"

namespace waam::analysis {
namespace fs = std::filesystem;

void WritePlanFiles(const planner::Plan& plan, const fs::path& out_dir, bool layer_images, bool quiet,
                    RunOutputs* outputs) {
  WritePlanH5(plan, outputs->Add(out_dir / "plan.h5"));
  if (!layer_images) return;
  Progress progress("pictures", plan.layers.size(), "layers", quiet);
  for (std::size_t i = 0; i < plan.layers.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "layer_%04zu.png", i);
    WriteLayerPng(plan.layers[i], plan.name, outputs->Add(out_dir / "layers" / name));
    progress.Update(i + 1);
  }
  progress.Finish();
}

// `waam plan` warns when the beads leave more than this share of the sliced area uncovered, per cent.
constexpr double kUncoveredWarningPct = 5.0;

namespace {

nlohmann::json MeshToJson(const planner::MeshReport& mesh) {
  return {
      {"source", mesh.source},
      {"binary_stl", mesh.binary},
      {"facets", mesh.facets},
      {"vertices", mesh.vertices},
      {"degenerate_facets", mesh.degenerate_facets},
      {"boundary_edges", mesh.boundary_edges},
      {"non_manifold_edges", mesh.non_manifold_edges},
      {"watertight", mesh.watertight},
      {"bbox_min_mm", {mesh.bbox_min.x(), mesh.bbox_min.y(), mesh.bbox_min.z()}},
      {"bbox_max_mm", {mesh.bbox_max.x(), mesh.bbox_max.y(), mesh.bbox_max.z()}},
  };
}

// plan.json's layer_details and uncovered: each layer's figures and the slice area the beads leave uncovered
// (planner/path/coverage.h; null where no layer is measured).
struct LayersJson {
  nlohmann::json details = nlohmann::json::array();
  nlohmann::json uncovered;
};

LayersJson LayersToJson(const planner::PlanResult& result) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const planner::PathStats& stats = result.stats;
  LayersJson out;
  double uncovered_sum = 0.0, area_sum = 0.0, uncovered_worst = 0.0;  // over the layers whose coverage is measured
  int worst_layer = -1;
  // Each layer's coverage on its own (each into its own slot, so the sums below do not depend on the thread count).
  std::vector<double> uncovered_of(result.plan.layers.size());
  ParallelFor(uncovered_of.size(), [&](std::size_t i) { uncovered_of[i] = planner::UncoveredArea(result.plan.layers[i]); });
  for (std::size_t i = 0; i < result.plan.layers.size(); ++i) {
    const planner::LayerPath& layer = result.plan.layers[i];
    const double area = planner::Area(layer.slice);
    const double uncovered = uncovered_of[i];
    const double uncovered_pct = area > 0.0 ? 100.0 * uncovered / area : 0.0;  // NaN stays NaN (JSON null)
    if (!std::isnan(uncovered)) {
      uncovered_sum += uncovered;
      area_sum += area;
      if (worst_layer < 0 || uncovered_pct > uncovered_worst) uncovered_worst = uncovered_pct, worst_layer = layer.index;
    }
    out.details.push_back({{"index", layer.index},
                           {"z_mm", layer.z_mm},
                           {"regions", layer.slice.size()},
                           {"area_mm2", area},
                           {"uncovered_pct", uncovered_pct},
                           {"passes", stats.passes_per_layer[i]},
                           {"path_elements", stats.path_elements_per_layer[i]},
                           {"points", layer.points.size()}});
  }
  out.uncovered = {{"pct", area_sum > 0.0 ? 100.0 * uncovered_sum / area_sum : kNaN},
                   {"worst_layer_pct", worst_layer >= 0 ? uncovered_worst : kNaN},
                   {"worst_layer", worst_layer}};
  return out;
}

// Weld travel speeds actually planned (they vary per point with bead_model csw), [min, max] mm/min; [0, 0] without
// a weld point.
nlohmann::json WeldSpeedRange(const planner::Plan& plan) {
  double speed_lo = 0.0, speed_hi = 0.0;
  bool any_weld = false;
  for (const planner::LayerPath& layer : plan.layers) {
    for (const planner::PathPoint& point : layer.points) {
      if (!point.weld) continue;
      const double v = point.speed_mm_s * 60.0;
      speed_lo = any_weld ? std::min(speed_lo, v) : v;
      speed_hi = any_weld ? std::max(speed_hi, v) : v;
      any_weld = true;
    }
  }
  return {speed_lo, speed_hi};
}

nlohmann::json SubVolumesToJson(const std::vector<planner::SubVolumeReport>& subs) {
  nlohmann::json sub_volumes = nlohmann::json::array();
  for (const planner::SubVolumeReport& sub : subs) {
    sub_volumes.push_back({{"name", sub.name},
                           {"direction", {sub.direction.x(), sub.direction.y(), sub.direction.z()}},
                           {"first_layer", sub.first_layer},
                           {"layers", sub.layers},
                           {"volume_mm3", sub.volume_mm3},
                           {"support_mm3", sub.support_mm3},
                           {"keep", sub.keep},
                           {"centroid_lean_deg", sub.centroid_lean_deg},
                           {"unwelded_mm3", sub.unwelded_mm3}});
  }
  return sub_volumes;
}

// Junction void filling (003 sec. 4.4): corrected corners and the mean shift per junction class.
nlohmann::json VoidFillingToJson(const Scenario& scenario, const planner::PlanResult& result) {
  std::map<std::string, std::pair<int, double>> by_class;
  for (const planner::CornerCorrection& c : result.void_corrections) {
    by_class[c.junction_class].first += 1;
    by_class[c.junction_class].second += c.shift_mm;
  }
  nlohmann::json classes = nlohmann::json::object();
  for (const auto& [name, count_sum] : by_class) {
    classes[name] = {{"corners", count_sum.first}, {"mean_shift_mm", count_sum.second / count_sum.first}};
  }
  return {{"mode", scenario.path.void_filling.mode},
          {"corrected_corners", result.void_corrections.size()},
          {"classes", classes}};
}

}  // namespace

nlohmann::json PlanToJson(const Scenario& scenario, const planner::PlanResult& result) {
  const planner::PathStats& stats = result.stats;
  LayersJson layers = LayersToJson(result);
  return {
      {"scenario", scenario.name},
      {"slicing", scenario.slicing.type},
      {"weld_speed_range_mm_min", WeldSpeedRange(result.plan)},
      {"pattern", scenario.path.pattern},
      {"overlap_model", scenario.path.overlap_model},
      {"bead_model", scenario.process.bead_model},
      {"bead_width_mm", result.bead_width_mm},
      {"contour_tolerance_mm", result.contour_tolerance_mm},
      {"travel_speed_mm_min", result.travel_speed_mm_min},
      {"speed_clamp", result.speed_clamp},
      {"layer_height_mm", result.layer_height_mm},
      {"bead_area_mm2", result.bead_area_mm2},
      {"bead_height_mm", result.bead_height_mm},
      {"layer_growth_mm", result.layer_growth_mm},
      {"layer_height_min_mm", result.layer_height_min_mm},
      {"layer_height_max_mm", result.layer_height_max_mm},
      {"speed_min_mm_min", result.speed_min_mm_min},
      {"speed_max_mm_min", result.speed_max_mm_min},
      {"layers_out_of_range", result.layers_out_of_range},
      {"mesh", MeshToJson(result.mesh_report)},
      {"layers", stats.layers},
      {"passes", stats.passes},
      {"passes_per_layer", stats.passes_per_layer},
      {"path_elements", stats.path_elements},
      {"path_elements_per_layer", stats.path_elements_per_layer},
      {"weld_length_mm", stats.weld_length_mm},
      {"travel_length_mm", stats.travel_length_mm},
      {"estimated_time_s", stats.estimated_time_s},  // = timeline.total_s
      // Where the build's time goes (docs/TIMELINE.md).
      {"timeline", TimelineToJson(result.timeline)},
      // What was planned otherwise than asked, one line each (e.g. a region the continuous pattern's decomposition
      // could not split, planned with the hybrid pattern); empty when everything went as asked.
      {"warnings", result.warnings},
      // Slice area the planned beads leave uncovered (planner/path/coverage.h); null when no layer is measured.
      {"uncovered", std::move(layers.uncovered)},
      {"retract", {{"retract_mm", scenario.path.retract_mm},
                   {"travels", result.retract.travels},
                   {"over_the_part", result.retract.via_top}}},
      {"void_filling", VoidFillingToJson(scenario, result)},
      {"layer_details", std::move(layers.details)},
      {"sub_volumes", SubVolumesToJson(result.sub_volumes)},
  };
}

nlohmann::json PlanDocument(const Scenario& scenario, const planner::PlanResult& result, const ImportReport& import) {
  nlohmann::json document = PlanToJson(scenario, result);
  if (scenario.program.present) document["import"] = ImportToJson(import);
  return document;
}

void WritePlanOutputs(const planner::Plan& plan, const nlohmann::json& document, const fs::path& out_dir,
                      bool layer_images, bool quiet) {
  ClaimOutputDirectory(out_dir);
  RunOutputs outputs(out_dir / "plan.json");
  WritePlanFiles(plan, out_dir, layer_images, quiet, &outputs);
  CheckInterrupt();  // a Ctrl-C while the outputs were written still ends the run as interrupted (exit 130)
  WriteFileAtomic(out_dir / "plan.json", JsonText(document) + "\n");
  outputs.Complete();
}

planner::PlanResult RunPlan(const PlanOptions& options, nlohmann::json* summary_out) {
  const Scenario scenario = LoadScenario(options.scenario, options.overrides);
  ClaimOutputDirectory(options.out_dir);

  planner::PlanResult result;
  ImportReport import;  // a scenario with a program: section
  {
    // The layer count is known only once the mesh is loaded; PlanScenario sets the bar's total.
    Progress progress("plan", 0, "layers", options.quiet);
    result = PlanScenarioOrProgram(scenario, &progress, &import);
  }
  // The timeline on the cell's axes (a program's plan has it from its import already).
  if (!scenario.program.present) AddCellTimeline(scenario, &result);

  const nlohmann::json summary = PlanDocument(scenario, result, import);
  WritePlanOutputs(result.plan, summary, options.out_dir, options.layer_images, options.quiet);
  // A pattern that does not suit the part is not an error (the plan is written) but worth a line even when quiet.
  // Over the whole part, so a last sliver of a slice (a handle's tip) does not raise it.
  const nlohmann::json& uncovered = summary["uncovered"];
  if (uncovered["pct"].is_number() && uncovered["pct"].get<double>() > kUncoveredWarningPct) {
    std::cerr << "waam: warning: path.pattern '" << NameOf(scenario.path.pattern) << "' leaves "
              << std::lround(uncovered["pct"].get<double>()) << " % of the sliced area without a bead (layer "
              << uncovered["worst_layer"].get<int>() << ": " << std::lround(uncovered["worst_layer_pct"].get<double>())
              << " %; plan.json uncovered); "
              << (scenario.path.pattern == planner::Pattern::kContour ? "a hybrid or continuous" : "a contour")
              << " pattern may cover it\n";
  }
  for (const std::string& warning : result.warnings) std::cerr << "waam: warning: " << warning << "\n";
  if (summary_out != nullptr) *summary_out = summary;
  return result;
}

}  // namespace waam::analysis
