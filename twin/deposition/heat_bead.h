// Beads shaped by the heat where they are laid: the plan's bead heights and widths scaled per layer by the
// bead-temperature model at each layer's interpass temperature (docs/compensation.md, "Heat into shape").
#pragma once

#include <vector>

#include "models/bead/bead_temperature_model.h"
#include "planner/path/tool_path.h"

namespace waam::twin {

// Per plan layer: the factors on the bead height and width the model gives at that layer's interpass temperature.
struct BeadHeatFactors {
  std::vector<double> height;
  std::vector<double> width;
};

// The factors of `model` at `interpass_c[l]` (degC, one per plan layer). Throws InputError for a temperature that
// is not a number.
BeadHeatFactors BeadFactorsAt(const models::BeadTemperatureModel& model, const std::vector<double>& interpass_c);

// `plan` with every point's bead_height_mm and bead_width_mm of layer l multiplied by the factors of layer l. A
// factor of exactly 1 leaves the value bit for bit. Throws InputError when the factors do not cover every layer or
// one is not positive.
planner::Plan ShapeBeadsByHeat(const planner::Plan& plan, const BeadHeatFactors& factors);

}  // namespace waam::twin
