// `waam thermal`: the thermal run of a planned scenario and its outputs (thermal.json last).
#include "analysis/thermal_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>

#include "analysis/cell_files.h"
#include "analysis/import_command.h"
#include "analysis/scenario_plan.h"
#include "analysis/plan_timeline.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/core/output_lock.h"
#include "models/core/progress.h"
#include "models/core/run_outputs.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::analysis {

namespace {

nlohmann::json BoxJson(const Eigen::AlignedBox3d& box) {
  return {{"min_mm", {box.min().x(), box.min().y(), box.min().z()}},
          {"max_mm", {box.max().x(), box.max().y(), box.max().z()}}};
}

// Largest finite value, NaN (null in JSON) when there is none.
double MaxFinite(double a, double b) {
  if (!std::isfinite(a)) return b;
  if (!std::isfinite(b)) return a;
  return std::max(a, b);
}

}  // namespace

nlohmann::json ThermalToJson(const Scenario& scenario, const ThermalRunResult& result) {
  const planner::InterpassSettings& interpass = scenario.process.interpass;
  const planner::ArcSettings& arc = scenario.process.arc;
  nlohmann::json layers = nlohmann::json::array();
  double max_interpass = std::numeric_limits<double>::quiet_NaN(), peak = max_interpass, interpass_wait = 0.0;
  for (const ThermalLayer& l : result.layers) {
    layers.push_back({{"layer", l.layer},
                      {"start_s", l.start_s},
                      {"end_s", l.end_s},
                      {"interpass_c", l.interpass_c},
                      {"peak_c", l.peak_c},
                      {"wait_s", l.wait_s},
                      {"interpass_reached", l.interpass_reached}});
    if (l.layer > 0) max_interpass = MaxFinite(max_interpass, l.interpass_c);
    peak = MaxFinite(peak, l.peak_c);
    interpass_wait += l.wait_s;
  }
  nlohmann::json probes = nlohmann::json::object();
  for (const ThermalProbeHistory& p : result.probes) {
    probes[p.name] = {{"position_mm", {p.p_mm.x(), p.p_mm.y(), p.p_mm.z()}},
                      {"max_c", p.max_c},
                      {"time_of_max_s", std::isnan(p.max_c) ? std::numeric_limits<double>::quiet_NaN()
                                                            : p.time_of_max_s}};
  }
  const twin::EnergyBalance& e = result.energy;
  nlohmann::json interpass_json = {{"max_c", interpass.max_c},
                                   {"at", interpass.at},
                                   {"min_layer_time_s", interpass.min_layer_time_s}};
  if (interpass.at == planner::InterpassAt::kProbe) interpass_json["probe"] = interpass.probe;
  return {
      {"scenario", scenario.name},
      {"build_time_s", result.timeline.total_s},
      {"total_wait_s", result.timeline.wait_s},
      {"interpass_wait_s", interpass_wait},
      {"max_interpass_c", max_interpass},
      {"peak_c", peak},
      {"timeline", TimelineToJson(result.timeline)},
      {"interpass", interpass_json},
      {"arc", {{"power_w", arc.power_w}, {"efficiency", arc.efficiency}, {"heat_w", result.heat_w}}},
      {"layers", layers},
      {"probes", probes},
      {"energy_balance",
       {{"arc_energy_j", result.arc_energy_j},
        {"efficiency", arc.efficiency},
        {"heat_input_j", e.input_j},
        {"stored_j", e.stored_j},
        {"lost_j", e.lost_j},
        {"convection_j", e.convection_j},
        {"radiation_j", e.radiation_j},
        {"table_j", e.table_j},
        {"relative_error", e.RelativeError()}}},
      {"solver",
       {{"cells", result.stats.cells},
        {"active_cells", result.stats.active_cells},
        {"steps", result.stats.steps},
        {"iterations", result.stats.iterations},
        {"wall_s", result.wall_s},
        {"cell_mm", result.settings.cell_mm},
        {"sample_s", scenario.thermal.sample_s}}},
      {"materials",
       {{"deposit", {{"name", result.settings.deposit.name}, {"source", result.settings.deposit.source}}},
        {"substrate", {{"name", result.settings.substrate.name}, {"source", result.settings.substrate.source}}}}},
      {"substrate", BoxJson(result.settings.substrate_box_mm)},
      {"deposit_box", BoxJson(result.settings.deposit_box_mm)},
  };
}

TimelineBuilder TimelineBuilderFor(const Scenario& scenario, const planner::Plan& plan) {
  auto cell = std::make_shared<const twin::CellModel>(LoadCell(scenario.cell));
  return [&scenario, &plan, cell](const std::vector<double>& extra_wait_s) {
    return CellTimeline(scenario, *cell, plan, extra_wait_s);
  };
}

ThermalRunResult ThermalPlanned(const Scenario& scenario, const planner::Plan& plan, const ThermalOptions& options) {
  ThermalSettingsFor(scenario, plan);  // bad input (a probe outside the metal) before anything is written
  ClaimOutputDirectory(options.out_dir);
  RemoveEarlierSummary(options.out_dir / "thermal.json");
  ThermalRunResult result = [&] {
    Progress progress("thermal", 0, "spans", options.quiet);
    ThermalRunResult r = RunThermalModel(scenario, plan, TimelineBuilderFor(scenario, plan), &progress);
    progress.Finish();
    return r;
  }();
  WriteThermalOutputs(scenario, result, options);
  return result;
}

nlohmann::json WriteThermalOutputs(const Scenario& scenario, const ThermalRunResult& result,
                                   const ThermalOptions& options) {
  ClaimOutputDirectory(options.out_dir);
  RunOutputs outputs(options.out_dir / "thermal.json");
  WriteThermalH5(result, outputs.Add(options.out_dir / "thermal.h5"));
  if (options.images) {
    WriteInterpassPng(result, scenario.process.interpass, scenario.name, outputs.Add(options.out_dir / "interpass.png"));
    WriteProbesPng(result, scenario.process.interpass, scenario.name, outputs.Add(options.out_dir / "probes.png"));
    // One colour range for every layer's map: the coolest and hottest metal of all of them.
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const ThermalLayerField& f : result.fields) {
      for (const float t : f.field.temperature_c) {
        if (std::isnan(t)) continue;
        lo = std::min(lo, static_cast<double>(t));
        hi = std::max(hi, static_cast<double>(t));
      }
    }
    for (const ThermalLayerField& f : result.fields) {
      char name[40];
      std::snprintf(name, sizeof(name), "maps/layer_%04d.png", f.layer);
      WriteTemperatureMapPng(f, result.settings.deposit_box_mm, lo, hi, scenario.name, outputs.Add(options.out_dir / name));
    }
  }
  CheckInterrupt();  // a Ctrl-C while the outputs were written still ends the run as interrupted (exit 130)
  nlohmann::json document = ThermalToJson(scenario, result);
  WriteFileAtomic(options.out_dir / "thermal.json", JsonText(document) + "\n");
  outputs.Complete();
  return document;
}

ThermalRunResult RunThermal(const ThermalOptions& options) {
  const Scenario scenario = LoadScenario(options.scenario, options.overrides);
  WAAM_THROW_UNLESS(scenario.thermal.given, options.scenario.string() << ": no thermal: section: waam thermal needs "
                                                                         "the metals and the plate (docs/THERMAL.md)");
  planner::PlanResult planned = PlanForCommand(scenario, options.quiet);
  return ThermalPlanned(scenario, planned.plan, options);
}

}  // namespace waam::analysis
