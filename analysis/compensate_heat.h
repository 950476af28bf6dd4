// Heat into shape for `waam compensate`: the thermal run of the nominal plan turned into per-layer bead factors and
// the distortion's thermal history (docs/compensation.md, "Heat into shape").
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/scenario.h"
#include "analysis/thermal_run.h"
#include "planner/path/tool_path.h"
#include "twin/compensation/compensation.h"

namespace waam::analysis {

// Per plan layer, what the thermal run gave the shape: the interpass temperature (degC; the plate's initial
// temperature where the run has none) and the peak temperature (degC).
std::vector<twin::LayerHeat> LayerHeatOf(const std::vector<double>& interpass_c, const std::vector<double>& peak_c,
                                         double initial_c);

// With thermal.shape in the scenario: runs the thermal model along `plan` (the scenario's cell timeline) and fills
// loop->bead_heat (thermal.shape.bead_model) and loop->distortion.layer_heat (thermal.shape.distortion; a model
// without reference_interpass_c takes the mean of the layers' interpass temperatures as its reference, i.e. it is
// taken as fitted on this build). Returns the record written under "heat" in compensate.json (null without
// thermal.shape). Throws InputError (thermal settings) and Interrupted.
nlohmann::json PrepareHeatShape(const Scenario& scenario, const planner::Plan& plan, bool quiet,
                                twin::CompensationOptions* loop);

}  // namespace waam::analysis
