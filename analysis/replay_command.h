// `waam thermal replay` and `waam fit thermal`: a build's process log drives the thermal model, its thermocouples
// are compared, and the uncertain parameters are fitted on a window of the log (docs/REPLAY.md).
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/replay_run.h"

namespace waam::analysis {

struct ReplayOptions {
  std::filesystem::path scenario;      // scenario YAML with thermal:, process.arc and replay: sections
  std::filesystem::path out_dir;       // output directory (created if missing)
  std::vector<std::string> overrides;  // --set key.path=value
  std::string windows;                 // "A:B,C:D" (s from the log's first row); empty = none
  std::filesystem::path parameters;    // a fitted file (waam fit thermal) whose `parameters` replace the scenario's
  bool quiet = false;                  // no log issues listed on stderr beyond their count
  bool images = true;                  // write probes_replay.png
};

struct ReplayRunResult {
  ReplayModel model;
  ThermalParameters parameters;       // what was replayed
  ReplaySimulation simulation;
  std::vector<std::pair<double, double>> windows;
  nlohmann::json document;            // replay.json
};

// Loads the scenario and its log (both checked before anything is written), replays the whole log and writes
// replay.h5, probes_replay.png and replay.json last, atomically, in a claimed output folder. Log issues are listed in
// replay.json and summarised on `err`. Throws InputError for bad input (one line naming file:line or key).
ReplayRunResult RunThermalReplay(const ReplayOptions& options, std::ostream& err);

// The scenario and its log loaded and resolved (ReadReplayLog, MakeReplayModel); `parameters_file` (may be empty)
// is a fitted file whose parameters replace the scenario's. Throws InputError.
ReplayModel LoadReplayModel(const std::filesystem::path& scenario, const std::vector<std::string>& overrides,
                            const std::filesystem::path& parameters_file = {});

// The parameters of a fitted file (`waam fit thermal -o`): {"parameters": {efficiency, convection_w_m2k,
// table_conductance_w_m2k, emissivity}}; keys absent keep `base`'s. Throws InputError naming the file and key.
ThermalParameters ReadThermalParameters(const std::filesystem::path& file, const ThermalParameters& base);
nlohmann::json ThermalParametersJson(const ThermalParameters& p);

// Prints the count of each kind of log issue and the first few of them, one line each.
void PrintLogIssues(const ReplayLog& log, bool all, std::ostream& err);
nlohmann::json LogIssuesJson(const ReplayLog& log);

// replay.h5: /time_s, /measured/<NAME> and /simulated/<NAME> (degC, NaN where none), /power_w, /arc_on, /head_mm
// (rows x 3, part frame). probes_replay.png: one panel per probe, measured against simulated over time.
void WriteReplayH5(const ReplayModel& model, const ReplaySimulation& simulation, const std::filesystem::path& path);
void WriteReplayPng(const ReplayModel& model, const ReplaySimulation& simulation,
                    const std::vector<std::pair<double, double>>& windows, const std::filesystem::path& path);

// `waam fit thermal`: see analysis/fit_command.h (FitOptions: scenario = data, free, window, output).
struct FitOptions;
struct FitOutcome;
namespace internal {
FitOutcome RunFitThermal(const FitOptions& options, std::ostream& out);
}  // namespace internal

}  // namespace waam::analysis
