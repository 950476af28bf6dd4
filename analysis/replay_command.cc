// `waam thermal replay`: the scenario and its process log in, replay.json, replay.h5 and probes_replay.png out.
#include "analysis/replay_command.h"

#include <map>
#include <ostream>

#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/core/output_lock.h"
#include "models/core/progress.h"
#include "models/core/run_outputs.h"

namespace waam::analysis {

ThermalParameters ReadThermalParameters(const std::filesystem::path& file, const ThermalParameters& base) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(ReadFile(file));
  } catch (const nlohmann::json::exception& e) {
    WAAM_THROW(file.string() << ": not JSON: " << e.what());
  }
  WAAM_THROW_UNLESS(doc.is_object() && doc.contains("parameters") && doc["parameters"].is_object(),
                    file.string() << ": no \"parameters\" object (a file written by waam fit thermal)");
  ThermalParameters p = base;
  const std::map<std::string, double*> keys = {{"efficiency", &p.efficiency},
                                               {"convection_w_m2k", &p.convection_w_m2k},
                                               {"table_conductance_w_m2k", &p.table_conductance_w_m2k},
                                               {"emissivity", &p.emissivity},
                                               {"clamp_conductance_factor", &p.clamp_factor}};
  for (const auto& [key, value] : doc["parameters"].items()) {
    const auto it = keys.find(key);
    WAAM_THROW_UNLESS(it != keys.end(), file.string() << ": parameters." << key << ": unknown (efficiency, "
                                                         "convection_w_m2k, table_conductance_w_m2k, emissivity, clamp_conductance_factor)");
    WAAM_THROW_UNLESS(value.is_number() && std::isfinite(value.get<double>()),
                      file.string() << ": parameters." << key << ": must be a number");
    *it->second = value.get<double>();
  }
  WAAM_THROW_UNLESS(p.efficiency > 0.0 && p.efficiency <= 1.0,
                    file.string() << ": parameters.efficiency = " << p.efficiency << ": must be in (0, 1]");
  WAAM_THROW_UNLESS(p.convection_w_m2k >= 0.0 && p.table_conductance_w_m2k >= 0.0 && p.emissivity <= 1.0 &&
                        p.clamp_factor >= 0.0,
                    file.string() << ": parameters: convection, conductance and clamp factor must be >= 0, "
                                     "emissivity <= 1");
  return p;
}

nlohmann::json ThermalParametersJson(const ThermalParameters& p) {
  return {{"efficiency", p.efficiency},
          {"convection_w_m2k", p.convection_w_m2k},
          {"table_conductance_w_m2k", p.table_conductance_w_m2k},
          {"emissivity", p.emissivity},
          {"clamp_conductance_factor", p.clamp_factor}};
}

ReplayModel LoadReplayModel(const std::filesystem::path& scenario_file, const std::vector<std::string>& overrides,
                            const std::filesystem::path& parameters_file) {
  const Scenario scenario = LoadScenario(scenario_file, overrides);
  WAAM_THROW_UNLESS(scenario.replay.given, scenario_file.string() << ": no replay: section: name the process log "
                                                                     "and its columns (docs/REPLAY.md)");
  ReplayModel model = MakeReplayModel(scenario, ReadReplayLog(scenario.replay));
  if (!parameters_file.empty()) model.parameters = ReadThermalParameters(parameters_file, model.parameters);
  return model;
}

nlohmann::json LogIssuesJson(const ReplayLog& log) {
  nlohmann::json issues = nlohmann::json::array();
  for (const LogIssue& i : log.issues) {
    issues.push_back({{"kind", i.kind}, {"line", i.line}, {"time_s", i.time_s}, {"detail", i.detail}});
  }
  return issues;
}

void PrintLogIssues(const ReplayLog& log, bool all, std::ostream& err) {
  if (log.issues.empty()) return;
  std::map<std::string, int> counts;
  for (const LogIssue& i : log.issues) ++counts[i.kind];
  err << "waam: " << log.file << ": " << log.issues.size() << " log issue(s):";
  for (const auto& [kind, n] : counts) err << " " << n << " " << kind;
  err << " (replay.json log_issues)\n";
  const std::size_t shown = all ? log.issues.size() : std::min<std::size_t>(log.issues.size(), 5);
  for (std::size_t k = 0; k < shown; ++k) {
    const LogIssue& i = log.issues[k];
    err << "waam:   " << log.file << ":" << i.line << ": " << i.kind << " at " << i.time_s << " s: " << i.detail << "\n";
  }
}

ReplayRunResult RunThermalReplay(const ReplayOptions& options, std::ostream& err) {
  ReplayRunResult result;
  result.model = LoadReplayModel(options.scenario, options.overrides, options.parameters);
  const ReplayModel& model = result.model;
  if (!options.windows.empty()) {
    std::string rest = options.windows;
    while (!rest.empty()) {
      const std::size_t comma = rest.find(',');
      result.windows.push_back(ParseLogWindow(rest.substr(0, comma), model.log, "--windows"));
      rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
    }
  }
  result.parameters = model.parameters;
  ClaimOutputDirectory(options.out_dir);
  RunOutputs outputs(options.out_dir / "replay.json");
  PrintLogIssues(model.log, !options.quiet, err);
  result.simulation = SimulateReplay(model, result.parameters);
  const ReplaySimulation& sim = result.simulation;
  WriteReplayH5(model, sim, outputs.Add(options.out_dir / "replay.h5"));
  if (options.images) WriteReplayPng(model, sim, result.windows, outputs.Add(options.out_dir / "probes_replay.png"));
  nlohmann::json& doc = result.document;
  doc = ReplayErrorsJson(model, sim, 0.0, model.log.time_s.back());
  doc.erase("from_s");
  doc.erase("to_s");
  doc["windows"] = nlohmann::json::array();
  for (const auto& [a, b] : result.windows) doc["windows"].push_back(ReplayErrorsJson(model, sim, a, b));
  doc["log"] = {{"file", model.log.file},
                {"rows", model.log.time_s.size()},
                {"duration_s", model.log.time_s.back()},
                {"gap_threshold_s", model.log.gap_s}};
  doc["log_issues"] = LogIssuesJson(model.log);
  doc["parameters"] = ThermalParametersJson(result.parameters);
  doc["energy_balance"] = {{"heat_input_j", sim.heat_input_j},
                           {"stored_j", sim.energy.stored_j},
                           {"lost_j", sim.energy.lost_j},
                           {"relative_error", sim.energy.RelativeError()}};
  doc["solver"] = {{"cells", sim.stats.cells}, {"active_cells", sim.stats.active_cells}, {"steps", sim.stats.steps},
                   {"iterations", sim.stats.iterations}, {"wall_s", sim.wall_s}};
  CheckInterrupt();
  WriteFileAtomic(options.out_dir / "replay.json", JsonText(doc) + "\n");
  outputs.Complete();
  return result;
}

}  // namespace waam::analysis
