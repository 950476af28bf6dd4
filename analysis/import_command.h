// `waam import`: read a robot program or G-code made elsewhere into the twin's plan and write what was understood
// (plan.json with an `import` section, plan.h5, layer pictures).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/scenario.h"
#include "models/core/progress.h"
#include "planner/planar_planner.h"
#include "planner/program/program_plan.h"
#include "planner/program/program_reader.h"

namespace waam::analysis {

struct ImportOptions {
  std::filesystem::path program;                 // the program file
  std::optional<planner::ProgramFormat> format;  // empty: from the extension or the first lines
  std::filesystem::path scenario;                // optional: the cell, process and program frame; empty = defaults
  std::filesystem::path out_dir;
  std::vector<std::string> overrides;            // --set key.path=value on the scenario
  bool quiet = false;
  bool layer_images = true;
  // Yaskawa INFORM: encoder pulses per degree of the arm (6) and of the station (2); empty = the scenario's
  // program.yaskawa settings.
  std::vector<double> pulses_per_deg;
  std::vector<double> station_pulses_per_deg;
};

// What the import understood besides the plan.
struct ImportReport {
  planner::ProgramFormat format = planner::ProgramFormat::kCsv;
  std::size_t motions = 0;
  std::map<std::string, std::size_t> motions_by_kind;
  std::size_t points = 0;                        // path points after circular moves are discretised
  std::vector<planner::ProgramWarning> warnings;
};

// The Yaskawa reader's pulses per degree: the scenario's program.yaskawa settings, replaced by `robot` (6 values) and
// `station` (2 values) when they are not empty. Throws InputError for a wrong count or a value not > 0.
planner::JbiReadOptions JbiOptionsOf(const Scenario& scenario, const std::vector<double>& robot = {},
                                     const std::vector<double>& station = {});

// The plan of a program read with the scenario's cell (user frame, kinematics) and process (bead width; bead height
// per point from the wire feed and the point's travel speed, eq. 3.3-3.4). Throws InputError for a bad program.
planner::PlanResult PlanFromProgram(const Scenario& scenario, const planner::ParsedProgram& program,
                                    ImportReport* report);

// The `import` section of plan.json: format, motions (count and by kind), points, warnings (what, count,
// first_line).
nlohmann::json ImportToJson(const ImportReport& report);

// Reads options.program (options.format, or from its extension and first lines; options.scenario is not read) and
// plans it with the cell and process of `scenario` (PlanFromProgram), which is named after the program file when it
// has no name. Throws InputError for a bad program (naming file and line).
planner::PlanResult ImportProgramInto(const ImportOptions& options, Scenario* scenario, ImportReport* report);

// plan.json of an imported program: PlanToJson with slicing and pattern "program" and the `import` section naming
// the program file.
nlohmann::json ImportedPlanToJson(const Scenario& scenario, const planner::PlanResult& result,
                                  const ImportReport& report, const std::filesystem::path& program);

// Reads the program, writes plan.h5, the layer pictures and plan.json (last). Returns the plan.json document.
nlohmann::json RunImport(const ImportOptions& options);

}  // namespace waam::analysis
