// ShapeBeadsByHeat: the bead-temperature model applied to a plan, layer by layer.
#include "twin/deposition/heat_bead.h"

#include <cmath>

#include "models/core/error.h"

namespace waam::twin {

BeadHeatFactors BeadFactorsAt(const models::BeadTemperatureModel& model, const std::vector<double>& interpass_c) {
  BeadHeatFactors f;
  f.height.reserve(interpass_c.size());
  f.width.reserve(interpass_c.size());
  for (std::size_t l = 0; l < interpass_c.size(); ++l) {
    WAAM_THROW_UNLESS(std::isfinite(interpass_c[l]),
                      "bead-temperature model: layer " << l << ": interpass temperature " << interpass_c[l]
                                                       << " degC is not a number");
    f.height.push_back(model.HeightFactor(interpass_c[l]));
    f.width.push_back(model.WidthFactor(interpass_c[l]));
  }
  return f;
}

planner::Plan ShapeBeadsByHeat(const planner::Plan& plan, const BeadHeatFactors& factors) {
  WAAM_THROW_UNLESS(factors.height.size() >= plan.layers.size() && factors.width.size() >= plan.layers.size(),
                    "bead shaping: " << factors.height.size() << " layer factors for " << plan.layers.size()
                                     << " layers: one per layer is needed");
  planner::Plan out = plan;
  for (std::size_t l = 0; l < out.layers.size(); ++l) {
    const double fh = factors.height[l], fw = factors.width[l];
    WAAM_THROW_UNLESS(fh > 0.0 && fw > 0.0, "bead shaping: layer " << l << ": factors " << fh << ", " << fw
                                                                    << ": must be > 0");
    for (planner::PathPoint& p : out.layers[l].points) {
      p.bead_height_mm *= fh;
      p.bead_width_mm *= fw;
    }
  }
  return out;
}

}  // namespace waam::twin
