// PrepareHeatShape: thermal run -> per-layer interpass and peak -> bead factors and the distortion's thermal history.
#include "analysis/compensate_heat.h"

#include <cmath>

#include "analysis/thermal_command.h"
#include "analysis/thermal_run.h"
#include "models/core/error.h"
#include "models/core/progress.h"

namespace waam::analysis {

std::vector<twin::LayerHeat> LayerHeatOf(const std::vector<double>& interpass_c, const std::vector<double>& peak_c,
                                         double initial_c) {
  std::vector<twin::LayerHeat> heat(interpass_c.size());
  for (std::size_t l = 0; l < heat.size(); ++l) {
    // The first layer of an interpass rule measured on the part (top_max) has no metal below it: the plate's
    // temperature. A layer whose peak was not sampled counts as fully heated (it was welded).
    heat[l].interpass_c = std::isfinite(interpass_c[l]) ? interpass_c[l] : initial_c;
    heat[l].peak_c = l < peak_c.size() && std::isfinite(peak_c[l]) ? peak_c[l] : INFINITY;
  }
  return heat;
}

nlohmann::json PrepareHeatShape(const Scenario& scenario, const planner::Plan& plan, bool quiet,
                                twin::CompensationOptions* loop) {
  const ThermalShape& shape = scenario.thermal.shape;
  if (!scenario.thermal.given || !shape.Any()) return nullptr;
  ThermalSettingsFor(scenario, plan);  // bad input before the run
  ThermalRunResult run = [&] {
    Progress progress("thermal", 0, "spans", quiet);
    ThermalRunResult r = RunThermalModel(scenario, plan, TimelineBuilderFor(scenario, plan), &progress);
    progress.Finish();
    return r;
  }();
  // A layer laid after an interpass wait meets the temperature the rule measured after the wait; one laid without a
  // wait (a continuous spiral) meets what the run sampled under its weld moves as they went (laid_on_c).
  std::vector<double> interpass(plan.layers.size(), NAN), peak(plan.layers.size(), NAN);
  for (const ThermalLayer& layer : run.layers) {
    if (layer.layer < 0 || static_cast<std::size_t>(layer.layer) >= plan.layers.size()) continue;
    interpass[layer.layer] = layer.wait_s > 0.0 || std::isnan(layer.laid_on_c) ? layer.interpass_c : layer.laid_on_c;
    peak[layer.layer] = layer.peak_c;
  }
  const std::vector<twin::LayerHeat> heat = LayerHeatOf(interpass, peak, scenario.thermal.InitialC());
  double interpass_wait_s = 0.0;
  for (const ThermalLayer& layer : run.layers) interpass_wait_s += layer.wait_s;
  std::vector<double> used_interpass;
  double mean = 0.0;
  for (const twin::LayerHeat& h : heat) {
    used_interpass.push_back(h.interpass_c);
    mean += h.interpass_c / static_cast<double>(heat.size());
  }
  nlohmann::json record = {{"interpass_c", used_interpass},
                           {"thermal_wall_s", run.wall_s},
                           {"build_time_s", run.timeline.total_s},  // the waits included
                           {"interpass_wait_s", interpass_wait_s},
                           {"bead_model", shape.bead_model_path},
                           {"distortion", shape.distortion}};
  if (shape.bead_model) {
    loop->bead_heat = twin::BeadFactorsAt(*shape.bead_model, used_interpass);
    record["bead_height_factor"] = loop->bead_heat.height;
    record["bead_width_factor"] = loop->bead_heat.width;
  }
  if (shape.distortion) {
    if (!std::isfinite(loop->params.reference_interpass_c)) loop->params.reference_interpass_c = mean;
    WAAM_THROW_UNLESS(loop->params.reference_interpass_c < loop->params.mechanical_melting_c,
                      "thermal.shape.distortion: the reference interpass temperature "
                          << loop->params.reference_interpass_c << " degC is not below the mechanical melting "
                          << loop->params.mechanical_melting_c << " degC of the distortion model");
    loop->distortion.layer_heat = heat;
    std::vector<double> factors;
    for (const twin::LayerHeat& h : heat) factors.push_back(loop->params.ThermalFactor(h.peak_c, h.interpass_c));
    record["reference_interpass_c"] = loop->params.reference_interpass_c;
    record["mechanical_melting_c"] = loop->params.mechanical_melting_c;
    record["strain_factor"] = factors;
  }
  return record;
}

}  // namespace waam::analysis
