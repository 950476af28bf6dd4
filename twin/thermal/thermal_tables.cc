// Resampling of a metal's thermal properties for the solver, and the checks of a material's tables.
#include "twin/thermal/thermal_tables.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"

namespace waam::twin::internal {
namespace {

// Substeps of the trapezoidal integration of the effective heat capacity inside one table segment: the latent
// heat's plateau starts and ends inside a segment, and 32 substeps put the enthalpy within 1/64 of a segment's
// latent share of the exact integral.
constexpr int kEnthalpySubsteps = 32;

void CheckColumn(const std::vector<double>& column, std::size_t rows, const char* what, const char* name,
                 const std::string& material) {
  WAAM_THROW_UNLESS(column.size() == rows, what << " " << material << ": " << name << " has " << column.size()
                                                << " rows, temperature_c has " << rows
                                                << ": each property must be a function of temperature");
  for (std::size_t i = 0; i < column.size(); ++i) {
    WAAM_THROW_UNLESS(std::isfinite(column[i]) && column[i] > 0.0,
                      what << " " << material << ": " << name << "[" << i << "] = " << column[i] << ": must be > 0");
  }
}

}  // namespace

void CheckThermalMaterial(const models::ThermalMaterial& m, const char* what) {
  const std::size_t rows = m.temperature_c.size();
  WAAM_THROW_UNLESS(rows > 0, what << " " << m.name << ": temperature_c is empty: a table needs at least one row");
  for (std::size_t i = 0; i < rows; ++i) {
    WAAM_THROW_UNLESS(std::isfinite(m.temperature_c[i]) && m.temperature_c[i] > -273.15,
                      what << " " << m.name << ": temperature_c[" << i << "] = " << m.temperature_c[i]
                           << ": must be above absolute zero");
    WAAM_THROW_UNLESS(i == 0 || m.temperature_c[i] > m.temperature_c[i - 1],
                      what << " " << m.name << ": temperature_c[" << i << "] = " << m.temperature_c[i]
                           << ": temperatures must be strictly increasing");
  }
  CheckColumn(m.conductivity_w_mk, rows, what, "conductivity_w_mk", m.name);
  CheckColumn(m.density_kg_m3, rows, what, "density_kg_m3", m.name);
  CheckColumn(m.specific_heat_j_kgk, rows, what, "specific_heat_j_kgk", m.name);
  WAAM_THROW_UNLESS(std::isfinite(m.solidus_c) && std::isfinite(m.liquidus_c) && m.liquidus_c >= m.solidus_c,
                    what << " " << m.name << ": liquidus_c = " << m.liquidus_c << " below solidus_c = " << m.solidus_c
                         << ": must be >= solidus_c");
  WAAM_THROW_UNLESS(std::isfinite(m.latent_heat_j_kg) && m.latent_heat_j_kg >= 0.0,
                    what << " " << m.name << ": latent_heat_j_kg = " << m.latent_heat_j_kg << ": must be >= 0");
  WAAM_THROW_UNLESS(m.emissivity >= 0.0 && m.emissivity <= 1.0,
                    what << " " << m.name << ": emissivity = " << m.emissivity << ": must be in [0, 1]");
}

ThermalPropertyTable::ThermalPropertyTable(const models::ThermalMaterial& material, double low_c, double high_c,
                                           double step_c, double reference_c, double liquid_conductivity_factor)
    : low_c_(low_c), step_c_(step_c), inverse_step_(1.0 / step_c), emissivity_(material.emissivity) {
  const int nodes = static_cast<int>(std::ceil((high_c - low_c) / step_c)) + 1;
  conductivity_.resize(nodes);
  enthalpy_.resize(nodes);
  enthalpy_[0] = 0.0;
  for (int i = 0; i < nodes; ++i) {
    const double t = low_c + i * step_c;
    // The enhanced conductivity of the stirred pool: the factor in full above the liquidus, ramped from 1 over the
    // mushy zone.
    const double range = material.liquidus_c - material.solidus_c;
    const double liquid = t >= material.liquidus_c ? 1.0
                          : t <= material.solidus_c ? 0.0
                                                    : (t - material.solidus_c) / std::max(range, 1e-12);
    conductivity_[i] = material.Conductivity(t) * (1.0 + (liquid_conductivity_factor - 1.0) * liquid);
    if (i == 0) continue;
    // Trapezoid rule on substeps of the segment [t - step, t].
    const double h = step_c / kEnthalpySubsteps;
    double sum = 0.5 * (material.EffectiveHeatCapacity(t - step_c) + material.EffectiveHeatCapacity(t));
    for (int s = 1; s < kEnthalpySubsteps; ++s) sum += material.EffectiveHeatCapacity(t - step_c + s * h);
    enthalpy_[i] = enthalpy_[i - 1] + sum * h;
  }
  const double shift = Enthalpy(reference_c);
  for (double& value : enthalpy_) value -= shift;
}

double ThermalPropertyTable::Temperature(double h_j_m3) const {
  // The first node above h (clamped so that a segment [i - 1, i] exists), then the linear inverse.
  auto upper = std::upper_bound(enthalpy_.begin() + 1, enthalpy_.end() - 1, h_j_m3);
  const int i = static_cast<int>(upper - enthalpy_.begin());
  const double s = (h_j_m3 - enthalpy_[i - 1]) / (enthalpy_[i] - enthalpy_[i - 1]);
  return low_c_ + (i - 1 + s) * step_c_;
}

}  // namespace waam::twin::internal
