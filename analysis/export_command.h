// `waam export`: the program of a scenario in one controller dialect (or G-code), as the cell check moves the cell.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analysis/scenario.h"
#include "planner/kinematics/cell_motion.h"
#include "planner/program/program_motion.h"
#include "planner/program/program_reader.h"
#include "planner/program/robot_program.h"

namespace waam::analysis {

struct ExportOptions {
  std::filesystem::path scenario;
  // empty: from the output file's extension, else the cell preset's dialect (fanuc_ls without a preset)
  std::optional<planner::ProgramFormat> format;
  std::filesystem::path out_file;
  std::vector<std::string> overrides;
  bool quiet = false;
  // yaskawa_jbi: the station's encoder pulses per degree (tilt, rotation); empty = the scenario's
  // program.yaskawa.station_pulses_per_deg.
  std::vector<double> station_pulses_per_deg;
};

struct ExportResult {
  planner::ProgramFormat format = planner::ProgramFormat::kFanucLs;
  std::size_t points = 0;
  std::size_t violations = 0;  // what the cell check found on the way (the program is written all the same)
};

// The program text of `program` in `format` for the cell `kin` (its user frame and torch); `jbi` gives the station's
// pulses per degree of a yaskawa_jbi job. Throws InputError for a dialect without a writer, or a JBI without them.
std::string WriteProgramText(planner::ProgramFormat format, const planner::RobotProgram& program,
                             const planner::CellKinematics& kin, const planner::JbiReadOptions& jbi = {});

// A program's files: the extension (".ls", ".src", ...) and the text of each (two for KUKA KRL: .src and .dat).
struct ProgramFiles {
  planner::ProgramFormat format = planner::ProgramFormat::kFanucLs;
  std::vector<std::pair<std::string, std::string>> files;
  std::size_t points = 0;
  std::size_t violations = 0;  // what the cell check found on the way (the program is written all the same)
};

// The program of an already planned `plan` of `scenario` in `format` (empty: the cell preset's dialect, fanuc_ls
// without a preset), as the cell check moves the cell along it. Throws InputError as WriteProgramText does.
ProgramFiles ExportPlan(const Scenario& scenario, const planner::Plan& plan,
                        std::optional<planner::ProgramFormat> format,
                        const std::vector<double>& station_pulses_per_deg, bool quiet);

// Plans the scenario (or reads its program), moves the cell along it as `waam check` does and writes the program
// atomically to out_file.
ExportResult RunExport(const ExportOptions& options);

}  // namespace waam::analysis
