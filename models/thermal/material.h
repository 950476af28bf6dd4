// Temperature-dependent thermal properties of a metal (deposit or plate), read from a cited data file.
#pragma once

#include <string>
#include <vector>

namespace waam::models {

// Thermophysical properties as functions of temperature, tabulated at increasing temperatures and interpolated
// linearly between rows (held constant beyond the first and last row). SI units inside.
struct ThermalMaterial {
  std::string name;       // e.g. "mild_steel"
  std::string source;     // the citation(s) of the data
  std::vector<double> temperature_c;                  // strictly increasing, degC
  std::vector<double> conductivity_w_mk;              // k(T) > 0, W/(m K)
  std::vector<double> density_kg_m3;                  // rho(T) > 0, kg/m^3
  std::vector<double> specific_heat_j_kgk;            // cp(T) > 0, J/(kg K), without the latent heat
  double solidus_c = 0.0;                             // degC
  double liquidus_c = 0.0;                            // degC, >= solidus_c
  double latent_heat_j_kg = 0.0;                      // released between solidus and liquidus, J/kg, >= 0
  double emissivity = 0.0;                            // surface emissivity in [0, 1] (default for radiation)

  double Conductivity(double t_c) const;   // W/(m K)
  double Density(double t_c) const;        // kg/m^3
  double SpecificHeat(double t_c) const;   // J/(kg K), latent heat not included
  // Volumetric enthalpy-rate form: rho(T) * cp(T) plus the latent heat spread evenly over [solidus, liquidus], J/(m^3 K).
  double EffectiveHeatCapacity(double t_c) const;
};

}  // namespace waam::models
