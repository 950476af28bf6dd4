// The replay of a process log through the thermal model, and the comparison with its thermocouples.
#include "analysis/replay_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "analysis/thermal_run.h"
#include "models/core/error.h"
#include "models/core/progress.h"

namespace waam::analysis {

namespace {

constexpr double kReplayNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

ReplayModel MakeReplayModel(const Scenario& scenario, ReplayLog log) {
  const ThermalSection& thermal = scenario.thermal;
  const ReplaySection& replay = scenario.replay;
  WAAM_THROW_UNLESS(thermal.given, scenario.file.string() << ": a replay needs the thermal model: add a thermal: "
                                                             "section (docs/THERMAL.md)");
  WAAM_THROW_UNLESS(replay.given, scenario.file.string() << ": no replay: section: name the process log and its "
                                                            "columns (docs/REPLAY.md)");
  ReplayModel model;
  model.bead_width_mm = replay.bead_width_mm;
  model.bead_height_mm = replay.bead_height_mm;
  model.probes = replay.probes;
  // The deposit: the bead below every arc-on move, half its width around the head.
  Eigen::AlignedBox3d beads;
  const Eigen::Vector3d half(0.5 * replay.bead_width_mm, 0.5 * replay.bead_width_mm, 0.0);
  for (std::size_t i = 0; i + 1 < log.time_s.size(); ++i) {
    if (!log.arc_on[i] || log.gap_before[i + 1]) continue;
    for (const Eigen::Vector3d& p : {log.head_mm[i], log.head_mm[i + 1]}) {
      beads.extend(p + half);
      beads.extend(p - half - Eigen::Vector3d(0, 0, replay.bead_height_mm));
    }
  }
  WAAM_THROW_UNLESS(!beads.isEmpty(), log.file << ": the arc never burns between two rows: nothing to replay");
  model.settings = SectionSettings(thermal, beads);
  twin::ThermalSettings& s = model.settings;
  if (!log.ambient_c.empty()) s.ambient_c = log.ambient_c.front();
  if (!log.table_c.empty()) s.table_c = log.table_c.front();
  for (const ThermalClamp& clamp : thermal.clamps) model.clamp_w_m2k.push_back(clamp.conductance_w_m2k);
  for (const ReplayProbe& probe : model.probes) CheckProbeInMetal(s, probe.at_mm, probe.where);
  model.parameters = {scenario.process.arc.efficiency, s.convection_w_m2k, s.table_conductance_w_m2k, s.emissivity,
                      thermal.clamp_conductance_factor};
  model.log = std::move(log);
  return model;
}

namespace {

twin::ThermalSettings ReplaySettings(const ReplayModel& model, const ThermalParameters& parameters) {
  WAAM_THROW_UNLESS(std::isfinite(parameters.efficiency) && parameters.efficiency > 0.0 &&
                        parameters.efficiency <= 1.0,
                    "arc efficiency = " << parameters.efficiency << ": must be in (0, 1]");
  twin::ThermalSettings settings = model.settings;
  settings.convection_w_m2k = parameters.convection_w_m2k;
  settings.table_conductance_w_m2k = parameters.table_conductance_w_m2k;
  settings.emissivity = parameters.emissivity;
  WAAM_THROW_UNLESS(std::isfinite(parameters.clamp_factor) && parameters.clamp_factor >= 0.0,
                    "clamp conductance factor = " << parameters.clamp_factor << ": must be >= 0");
  for (std::size_t k = 0; k < settings.clamps.size(); ++k) {
    settings.clamps[k].conductance_w_m2k = model.clamp_w_m2k[k] * parameters.clamp_factor;
  }
  return settings;
}

}  // namespace

ReplayRun::ReplayRun(const ReplayModel& model, const ThermalParameters& parameters)
    : model_(&model), parameters_(parameters), sim_(ReplaySettings(model, parameters)) {
  // The probes are recorded inside the solver's batches (a TemperatureAt query would end the batch at every row).
  for (const ReplayProbe& probe : model.probes) sim_.AddProbe(probe.at_mm);
}

void ReplayRun::AdvanceTo(double end_s) {
  const ReplayLog& log = model_->log;
  const auto start = std::chrono::steady_clock::now();
  const bool boundaries = !log.ambient_c.empty() || !log.table_c.empty();
  const twin::ThermalSettings& settings = model_->settings;
  for (std::size_t& i = next_row_; i < log.time_s.size() && log.time_s[i] <= end_s; ++i) {
    if (i > 0) {
      const double seconds = log.time_s[i] - log.time_s[i - 1];
      if (log.arc_on[i - 1] && !log.gap_before[i]) {
        const double heat_w = parameters_.efficiency * log.power_w[i - 1];
        sim_.Weld(log.head_mm[i - 1], log.head_mm[i], model_->bead_width_mm, model_->bead_height_mm, heat_w,
                  seconds);
        heat_input_j_ += heat_w * seconds;
      } else {
        sim_.Cool(seconds);
      }
    }
    if (boundaries) {
      sim_.SetBoundaryTemperatures(log.ambient_c.empty() ? settings.ambient_c : log.ambient_c[i],
                                   log.table_c.empty() ? settings.table_c : log.table_c[i]);
    }
    records_.push_back(sim_.RecordProbes());
    if (i % 64 == 0) CheckInterrupt();
  }
  wall_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void ReplayRun::AdvanceThrough(double end_s) {
  AdvanceTo(end_s);
  const std::vector<double>& time_s = model_->log.time_s;
  if (records_.empty()) return;
  const std::size_t last = records_.back();  // the record of the last row up to end_s
  while (!sim_.ProbeRecordSolved(last) && next_row_ < time_s.size()) AdvanceTo(time_s[next_row_]);
}

std::vector<std::vector<double>> ReplayRun::ProbesTo(double end_s) const {
  const std::vector<double>& time_s = model_->log.time_s;
  std::vector<std::vector<double>> probe_c(model_->probes.size(), std::vector<double>(time_s.size(), kReplayNaN));
  for (std::size_t i = 0; i < records_.size() && time_s[i] <= end_s; ++i) {
    const std::vector<double> values = sim_.ProbeRecord(records_[i]);
    for (std::size_t p = 0; p < probe_c.size(); ++p) probe_c[p][i] = values[p];
  }
  return probe_c;
}

ReplaySimulation ReplayRun::Result() const {
  const auto start = std::chrono::steady_clock::now();
  ReplaySimulation out;
  out.probe_c = ProbesTo(std::numeric_limits<double>::infinity());
  out.energy = sim_.Energy();
  out.stats = sim_.Stats();
  out.heat_input_j = heat_input_j_;
  out.wall_s = wall_s_ + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

ReplaySimulation SimulateReplay(const ReplayModel& model, const ThermalParameters& parameters, double end_s) {
  ReplayRun run(model, parameters);
  run.AdvanceTo(end_s);
  return run.Result();
}

ReplayErrors CompareProbe(const std::vector<double>& time_s, const std::vector<double>& measured,
                          const std::vector<double>& simulated, double from_s, double to_s, bool outside) {
  ReplayErrors e;
  double sum_sq = 0.0, sum_abs = 0.0, sum_rel = 0.0;
  std::size_t n_rel = 0;
  e.peak_measured_c = e.peak_simulated_c = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < time_s.size(); ++i) {
    const double t = time_s[i];
    if ((t < from_s || t > to_s) != outside || std::isnan(measured[i]) || std::isnan(simulated[i])) continue;
    const double error = simulated[i] - measured[i];
    ++e.n;
    sum_sq += error * error;
    sum_abs += std::abs(error);
    if (std::abs(measured[i]) >= 1.0) {
      sum_rel += std::abs(error) / std::abs(measured[i]);
      ++n_rel;
    }
    if (std::abs(error) > e.max_error_c) {
      e.max_error_c = std::abs(error);
      e.max_error_time_s = t;
    }
    if (measured[i] > e.peak_measured_c) {
      e.peak_measured_c = measured[i];
      e.peak_measured_time_s = t;
    }
    if (simulated[i] > e.peak_simulated_c) {
      e.peak_simulated_c = simulated[i];
      e.peak_simulated_time_s = t;
    }
  }
  if (e.n == 0) {
    e.rmse_c = e.mae_c = e.mape_pct = e.peak_measured_c = e.peak_simulated_c = kReplayNaN;
    return e;
  }
  e.rmse_c = std::sqrt(sum_sq / static_cast<double>(e.n));
  e.mae_c = sum_abs / static_cast<double>(e.n);
  e.mape_pct = n_rel > 0 ? 100.0 * sum_rel / static_cast<double>(n_rel) : kReplayNaN;
  return e;
}

namespace {

nlohmann::json ErrorsJson(const ReplayErrors& e) {
  // NaN (no row compared) is written as null.
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"n", e.n},
          {"rmse_c", number(e.rmse_c)},
          {"mae_c", number(e.mae_c)},
          {"mape_pct", number(e.mape_pct)},
          {"max_error_c", number(e.n ? e.max_error_c : kReplayNaN)},
          {"max_error_time_s", number(e.n ? e.max_error_time_s : kReplayNaN)},
          {"peak_measured_c", number(e.peak_measured_c)},
          {"peak_measured_time_s", number(e.n ? e.peak_measured_time_s : kReplayNaN)},
          {"peak_simulated_c", number(e.peak_simulated_c)},
          {"peak_simulated_time_s", number(e.n ? e.peak_simulated_time_s : kReplayNaN)}};
}

}  // namespace

nlohmann::json ReplayErrorsJson(const ReplayModel& model, const ReplaySimulation& simulation, double from_s,
                                double to_s, bool outside) {
  nlohmann::json probes = nlohmann::json::object();
  // Overall: every probe's rows, one after the other, as one series.
  std::vector<double> time, measured, simulated;
  for (std::size_t p = 0; p < model.probes.size(); ++p) {
    const ReplayErrors e = CompareProbe(model.log.time_s, model.log.probe_c[p], simulation.probe_c[p], from_s, to_s, outside);
    nlohmann::json j = ErrorsJson(e);
    j["column"] = model.probes[p].column;
    j["at_mm"] = {model.probes[p].at_mm.x(), model.probes[p].at_mm.y(), model.probes[p].at_mm.z()};
    probes[model.probes[p].name] = j;
    time.insert(time.end(), model.log.time_s.begin(), model.log.time_s.end());
    measured.insert(measured.end(), model.log.probe_c[p].begin(), model.log.probe_c[p].end());
    simulated.insert(simulated.end(), simulation.probe_c[p].begin(), simulation.probe_c[p].end());
  }
  nlohmann::json doc = {{"probes", probes},
                        {"overall", ErrorsJson(CompareProbe(time, measured, simulated, from_s, to_s, outside))}};
  if (!outside) doc["from_s"] = from_s, doc["to_s"] = to_s;
  return doc;
}

std::pair<double, double> ParseLogWindow(const std::string& text, const ReplayLog& log, const std::string& what) {
  const std::size_t colon = text.find(':');
  double a = kReplayNaN, b = kReplayNaN;
  if (colon != std::string::npos) {
    const std::string first = text.substr(0, colon), second = text.substr(colon + 1);
    char* end = nullptr;
    a = std::strtod(first.c_str(), &end);
    if (first.empty() || end != first.c_str() + first.size()) a = kReplayNaN;
    b = std::strtod(second.c_str(), &end);
    if (second.empty() || end != second.c_str() + second.size()) b = kReplayNaN;
  }
  WAAM_THROW_UNLESS(std::isfinite(a) && std::isfinite(b) && a < b,
                    what << " '" << text << "': expected START:END in seconds from the log's first row, START < END");
  const double last = log.time_s.back();
  WAAM_THROW_UNLESS(a >= 0.0 && b <= last, what << " '" << text << "': outside the log " << log.file << ", which runs "
                                                << "from 0 to " << last << " s");
  return {a, b};
}

}  // namespace waam::analysis
