// `waam plan`: plan a scenario and write plan.json, plan.h5 and one PNG per layer.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/import_command.h"
#include "analysis/scenario.h"
#include "planner/planar_planner.h"

namespace waam {
class RunOutputs;
}  // namespace waam

namespace waam::analysis {

struct PlanOptions {
  std::filesystem::path scenario;   // scenario YAML
  std::filesystem::path out_dir;    // output directory (created if missing)
  std::vector<std::string> overrides;  // "key.path=value" scenario overrides (--set)
  bool quiet = false;               // no progress bar
  bool layer_images = true;         // write <out_dir>/layers/layer_NNNN.png
};

// Runs the planner and writes every output atomically; plan.json is written last, so its presence marks a complete
// run. Returns the planning result, and the plan.json document in `summary` when not null. Throws InputError for bad
// scenarios and meshes.
planner::PlanResult RunPlan(const PlanOptions& options, nlohmann::json* summary = nullptr);

// The plan.json document (the public contract: field names are documented in docs/OUTPUTS.md).
nlohmann::json PlanToJson(const Scenario& scenario, const planner::PlanResult& result);

// plan.json of a planned scenario: PlanToJson, with the `import` section when the plan came from its program.
nlohmann::json PlanDocument(const Scenario& scenario, const planner::PlanResult& result, const ImportReport& import);

// Writes what `waam plan` (and `waam import`) writes for a plan already made into `out_dir` (claimed first; plan.h5,
// layers/*.png with `layer_images`, then `document` as plan.json, last, all atomically). Throws InputError (the
// folder is held by another process) and OutputError.
void WritePlanOutputs(const planner::Plan& plan, const nlohmann::json& document, const std::filesystem::path& out_dir,
                      bool layer_images, bool quiet);

// Writes every layer's path points to an HDF5 file (see docs/OUTPUTS.md for the layout).
void WritePlanH5(const planner::Plan& plan, const std::filesystem::path& path);

// Writes plan.h5 and, with `layer_images`, layers/layer_NNNN.png into `out_dir`, each recorded in `outputs` (so an
// unfinished run removes them); shared by `waam plan` and `waam import`.
void WritePlanFiles(const planner::Plan& plan, const std::filesystem::path& out_dir, bool layer_images, bool quiet,
                    RunOutputs* outputs);

// Draws one layer of the part named `part`: the slice, the weld path in sequence colours, travel moves dashed, starts
// and stops marked, with axes in mm, a colour bar of the path length and a title (analysis/picture_frame.h).
void WriteLayerPng(const planner::LayerPath& layer, const std::string& part, const std::filesystem::path& path);

}  // namespace waam::analysis
