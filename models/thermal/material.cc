// Linear interpolation of the tabulated thermal properties of a metal.
#include "models/thermal/material.h"

#include <algorithm>

#include "models/core/error.h"

namespace waam::models {
namespace {

// Value of the column `values` at `t_c`, linear between the rows of `temperature_c`, held beyond the ends.
double Interpolate(const std::vector<double>& temperature_c, const std::vector<double>& values, double t_c) {
  WAAM_DEMAND(!temperature_c.empty() && temperature_c.size() == values.size());
  if (t_c <= temperature_c.front()) return values.front();
  if (t_c >= temperature_c.back()) return values.back();
  const auto upper = std::upper_bound(temperature_c.begin(), temperature_c.end(), t_c);
  const std::size_t i = static_cast<std::size_t>(upper - temperature_c.begin());
  const double s = (t_c - temperature_c[i - 1]) / (temperature_c[i] - temperature_c[i - 1]);
  return values[i - 1] + s * (values[i] - values[i - 1]);
}

}  // namespace

double ThermalMaterial::Conductivity(double t_c) const {
  return Interpolate(temperature_c, conductivity_w_mk, t_c);
}

double ThermalMaterial::Density(double t_c) const { return Interpolate(temperature_c, density_kg_m3, t_c); }

double ThermalMaterial::SpecificHeat(double t_c) const {
  return Interpolate(temperature_c, specific_heat_j_kgk, t_c);
}

double ThermalMaterial::EffectiveHeatCapacity(double t_c) const {
  double c = Density(t_c) * SpecificHeat(t_c);
  if (latent_heat_j_kg > 0.0 && liquidus_c > solidus_c && t_c >= solidus_c && t_c <= liquidus_c) {
    c += Density(t_c) * latent_heat_j_kg / (liquidus_c - solidus_c);
  }
  return c;
}

}  // namespace waam::models
