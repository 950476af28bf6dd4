// `waam simulate`: plan a scenario, deposit it in the voxel twin, scan it, and write simulate.json, part.stl,
// part.h5 and pictures.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/scenario.h"
#include "planner/mesh/triangle_mesh.h"
#include "planner/planar_planner.h"
#include "planner/scenario/scenario.h"
#include "twin/simulation.h"

namespace waam::analysis {

struct SimulateOptions {
  std::filesystem::path scenario;   // scenario YAML
  std::filesystem::path out_dir;    // output directory (created if missing)
  bool quiet = false;               // no progress bar
  bool images = true;               // write the PNGs
  std::vector<std::string> overrides;  // "key.path=value" scenario overrides (--set)
};

// Plans the scenario (as `waam plan` does), then SimulatePlanned. Returns the twin's measures.
// Throws InputError for bad scenarios, meshes and settings (voxel limit included).
twin::TwinMeasures RunSimulate(const SimulateOptions& options);

// Deposits and measures an already planned scenario and writes every output atomically: part.stl, part.h5,
// top_height.png, section_xz.png, section_yz.png, deviation_map.png, and simulate.json last (its presence marks a
// complete run). The target of the deviation and voids is `planned.mesh` when it has facets.
twin::TwinResult SimulatePlanned(const Scenario& scenario, const planner::PlanResult& planned,
                                 const SimulateOptions& options);

// Refuses a build that cannot fit in simulation.max_voxels: the planned bead volume in voxels against the limit.
// Throws InputError naming the scenario file and both keys.
void CheckVoxelBudget(const Scenario& scenario, const planner::Plan& plan);

// The part.stl surface of `grid` (twin::ExtractVoxelSurface); past 5 M exposed voxel faces or facets it is taken
// from a coarser copy of the grid (twin::Coarsen, factor 2 to 8, written to `factor`; 1 for the grid itself).
planner::TriangleMesh PartSurface(const twin::VoxelGrid& grid, int* factor);

// Writes what `waam simulate` writes for a build already simulated into `out_dir` (claimed first; part.stl,
// part.h5, the PNGs with `images`, simulate.json last, all atomically) and returns the simulate.json document
// (SimulationToJson with the part.stl fields stl_voxel_mm, stl_facets and performance.surface_s). Throws InputError
// and OutputError.
nlohmann::json WriteSimulateOutputs(const Scenario& scenario, const planner::PlanResult& planned,
                                    const twin::TwinResult& result, const std::filesystem::path& out_dir,
                                    bool images);

// The simulate.json document (the public contract; fields documented in `waam simulate --help`).
nlohmann::json SimulationToJson(const Scenario& scenario, const planner::PlanResult& planned,
                                const twin::TwinResult& result);

// The notes simulate.json and the bench report give where the scenario's own settings explain a large deviation:
// layers planned thinner or thicker than a layer of beads grows (slicing.layer_height_mm against the bead laid),
// and walls thinner than the bead (path.bead_width_mm against the narrowest sliced wall). Empty when neither holds.
std::vector<std::string> SimulationNotes(const planner::PlanResult& planned);

// Writes the voxel grid and the top height map to HDF5: /voxels/{ijk (N x 3 int32), bead (N uint32),
// layer (N int32), time_s (N float32)}, /top_height_mm (ny x nx float32, NaN where empty), /beads table,
// attributes voxel_mm and origin (mm).
void WriteSimulationH5(const twin::TwinResult& result, const std::filesystem::path& path);

// Pictures: top height map (colour by height), vertical sections through the part's middle along x and y
// (colour by layer), and the top view of the signed deviation (blue below, red above the target). Each has a title
// naming `part` and the quantity, axes in mm and a colour bar with its unit (analysis/picture_frame.h).
void WriteHeightMapPng(const twin::HeightMap& map, const std::string& part, const std::filesystem::path& path);
void WriteSectionPng(const twin::TwinResult& result, int axis, const std::string& part,
                     const std::filesystem::path& path);
void WriteDeviationPng(const twin::TwinResult& result, const std::string& part,
                       const std::filesystem::path& path);

}  // namespace waam::analysis
