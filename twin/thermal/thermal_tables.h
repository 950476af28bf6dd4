// A metal's thermal properties resampled on a uniform temperature grid: conductivity, volumetric enthalpy (latent
// heat included) and its inverse, each looked up in O(1) or O(log n) inside the solver's loops.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "models/thermal/material.h"

namespace waam::twin::internal {

// Volumetric enthalpy H(T) = integral of ThermalMaterial::EffectiveHeatCapacity from `reference_c`, tabulated every
// `step_c` between `low_c` and `high_c` and linear in between (extrapolated linearly with the end slopes beyond).
class ThermalPropertyTable {
 public:
  ThermalPropertyTable() = default;
  // Throws nothing; the material must already be valid (CheckThermalMaterial). The conductivity is multiplied by
  // `liquid_conductivity_factor` above the liquidus (ramped from 1 across the mushy zone).
  ThermalPropertyTable(const models::ThermalMaterial& material, double low_c, double high_c, double step_c,
                       double reference_c, double liquid_conductivity_factor = 1.0);

  // Inline: the solver calls these for every cell of every step.
  double Conductivity(double t_c) const {  // W/(m K)
    int i = 0;
    const double s = std::clamp(Position(t_c, &i), 0.0, 1.0);
    return conductivity_[i] + s * (conductivity_[i + 1] - conductivity_[i]);
  }
  double Enthalpy(double t_c) const {  // J/m^3, 0 at the reference temperature
    int i = 0;
    const double s = Position(t_c, &i);
    return enthalpy_[i] + s * (enthalpy_[i + 1] - enthalpy_[i]);
  }
  // dH/dT, J/(m^3 K): the slopes of the table's segments, taken at their midpoints and linear in between, so that
  // the capacity is continuous in t_c (a step's solution then moves continuously with its inputs: docs/THERMAL.md,
  // "Differencing a run"); constant beyond the first and last midpoints.
  double Capacity(double t_c) const {
    const double x = (t_c - low_c_) * inverse_step_ - 0.5;
    const int last = static_cast<int>(enthalpy_.size()) - 3;
    const int i = std::clamp(static_cast<int>(std::floor(x)), 0, last);
    const double s = std::clamp(x - i, 0.0, 1.0);
    const double a = enthalpy_[i + 1] - enthalpy_[i], b = enthalpy_[i + 2] - enthalpy_[i + 1];
    return (a + s * (b - a)) * inverse_step_;
  }
  double Temperature(double h_j_m3) const;  // inverse of Enthalpy, degC
  // The same, searching the table from the segment of `hint_c` (a temperature near the answer, degC): the result is
  // identical to Temperature(h_j_m3), found in a few steps when the hint is close.
  double Temperature(double h_j_m3, double hint_c) const {
    // The first node above h in [1, last] (the same node as the binary search above), walked to from the hint's.
    constexpr int kWalk = 8;
    const int last = static_cast<int>(enthalpy_.size()) - 1;
    int i = 0;
    Position(hint_c, &i);
    i = std::clamp(i + 1, 1, last);
    int steps = 0;
    while (i > 1 && enthalpy_[i - 1] > h_j_m3 && steps++ < kWalk) --i;
    while (i < last && enthalpy_[i] <= h_j_m3 && steps++ < kWalk) ++i;
    if (steps > kWalk) return Temperature(h_j_m3);
    const double s = (h_j_m3 - enthalpy_[i - 1]) / (enthalpy_[i] - enthalpy_[i - 1]);
    return low_c_ + (i - 1 + s) * step_c_;
  }
  double emissivity() const { return emissivity_; }

 private:
  // The segment index (clamped) and the fraction within it.
  double Position(double t_c, int* segment) const {
    const double x = (t_c - low_c_) * inverse_step_;
    const int last = static_cast<int>(enthalpy_.size()) - 2;
    int i = static_cast<int>(std::floor(x));
    i = std::clamp(i, 0, last);
    *segment = i;
    return x - i;
  }

  double low_c_ = 0.0;
  double step_c_ = 1.0;
  double inverse_step_ = 1.0;  // 1 / step_c_ (exact for the solver's 1 K step)
  double emissivity_ = 0.0;
  std::vector<double> conductivity_;  // W/(m K) at the nodes
  std::vector<double> enthalpy_;      // J/m^3 at the nodes, strictly increasing
};

// Throws InputError naming `what` (e.g. "thermal deposit material mild_steel") when the tables are not a function
// of temperature (sizes differ, temperatures not strictly increasing), a property is not > 0, liquidus < solidus,
// the latent heat is negative or the emissivity is outside [0, 1].
void CheckThermalMaterial(const models::ThermalMaterial& material, const char* what);

}  // namespace waam::twin::internal
