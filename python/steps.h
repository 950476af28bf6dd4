// The result objects of plan, check and simulate (python/step_bindings.cc), shared with the commands and sweeps.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/import_command.h"
#include "planner/planar_planner.h"
#include "python/bindings.h"
#include "twin/cell/cell_check.h"
#include "twin/simulation.h"

namespace waam::python {

// A plan and its points as one row-major (points x 11) table; layer i is rows [offsets[i], offsets[i + 1]).
struct PlanHolder {
  std::shared_ptr<const ScenarioHolder> scenario;
  planner::PlanResult result;
  analysis::ImportReport import;
  std::optional<std::filesystem::path> imported;  // the program file of import_program
  std::vector<double> table;
  std::vector<std::size_t> offsets;
};

struct CheckHolder {
  std::shared_ptr<const ScenarioHolder> scenario;
  std::shared_ptr<const PlanHolder> plan;
  twin::CheckReport report;
  nlohmann::json document;     // check.json without the viewer section
};

struct SimulateHolder {
  std::shared_ptr<const ScenarioHolder> scenario;
  std::shared_ptr<const PlanHolder> plan;
  std::optional<twin::TwinResult> result;  // set by simulate
  nlohmann::json document;        // simulate.json without the part.stl fields
  std::vector<std::int32_t> ijk;  // voxels x 3, as part.h5 /voxels/ijk
  double voxel_mm = 0.0;  // voxel (i, j, k) covers [i, i + 1) x voxel_mm along x from the part frame's origin
};

// Plans the scenario as `waam plan` does (GIL released by the caller). Throws InputError.
std::shared_ptr<PlanHolder> PlanOf(const std::shared_ptr<const ScenarioHolder>& scenario);
// Fills the plan's table and layer offsets from its result.
void FillTable(PlanHolder* plan);
// plan.json of a plan.
nlohmann::json PlanDocument(const PlanHolder& plan);

// save(dir) of each result: the command's files, by its writers. Throw InputError and OutputError.
void SavePlan(const PlanHolder& plan, const std::filesystem::path& dir, bool images);
void SaveCheck(const CheckHolder& check, const std::filesystem::path& dir, bool images);
void SaveSimulate(const SimulateHolder& part, const std::filesystem::path& dir, bool images);

}  // namespace waam::python
