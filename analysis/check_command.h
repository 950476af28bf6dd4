// `waam check`: plan a scenario, run its path on the MuJoCo cell and write check.json, pictures and the program.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/scenario.h"
#include "planner/mesh/triangle_mesh.h"
#include "planner/path/tool_path.h"
#include "planner/scenario/scenario.h"
#include "twin/cell/cell_check.h"

namespace waam::analysis {

struct CheckOptions {
  std::filesystem::path scenario;  // scenario YAML
  std::filesystem::path out_dir;   // output directory (created if missing)
  std::vector<std::string> overrides;  // "key.path=value" scenario overrides (--set)
  bool quiet = false;              // no progress bar
  bool images = true;              // cell_worst.png, joints.png
  bool program = true;             // program.csv, program.ls
  bool viewer = true;              // viewer.html (with images only)
  const planner::TriangleMesh* target = nullptr;  // the part, drawn as a ghost in viewer.html (may be null)
};

// Plans the scenario (planner::PlanScenario), checks the path on the cell and writes the outputs (check.json last).
// Throws InputError for a bad scenario, mesh or cell model; violations are in the report, not exceptions.
twin::CheckReport RunCheck(const CheckOptions& options);

// Checks an already planned `plan` of `scenario` and writes the outputs (check.json last).
twin::CheckReport RunCheckOnPlan(const Scenario& scenario, const planner::Plan& plan,
                                 const CheckOptions& options);

// Writes what `waam check` writes for a check already made of `plan` on `cell` into options.out_dir (claimed first;
// program.csv/.ls with options.program, cell_worst.png, joints.png and viewer.html with options.images, check.json
// last) and returns the check.json document. Throws InputError and OutputError.
nlohmann::json WriteCheckOutputs(const Scenario& scenario, const planner::Plan& plan, const twin::CellModel& cell,
                                 const twin::CheckReport& report, const CheckOptions& options);

// check.json without the viewer section: CheckToJson, and the `tool` section when the plan moves a program's own
// tool instead of the cell's torch.
nlohmann::json CheckPlanToJson(const Scenario& scenario, const twin::CellModel& cell, const planner::Plan& plan,
                               const twin::CheckReport& report);

// The check.json document (field names are the public contract documented in docs/CELL.md).
nlohmann::json CheckToJson(const Scenario& scenario, const std::filesystem::path& mjcf,
                           const twin::CheckReport& report);

// Draws the cell's collision shapes at the report's worst sample (side and top views) with the path and the
// violation marked, under a title naming the part (`part_name`) and the sample shown.
void WriteCellPng(const twin::CellModel& cell, const planner::CellKinematics& kin, const planner::Plan& plan,
                  const twin::CheckReport& report, const std::string& part_name, const std::filesystem::path& path);

// Plots the eight axis angles (deg) against time (s) with their limits, under a title naming the part (`part_name`).
void WriteJointPlots(const planner::CellKinematics& kin, const twin::CheckReport& report, const std::string& part_name,
                     const std::filesystem::path& path);

}  // namespace waam::analysis
