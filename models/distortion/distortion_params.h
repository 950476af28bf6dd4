// Parameters of the inherent-strain distortion model: shrinkage strains, their heat-input dependence, the substrate.
#pragma once

#include <array>
#include <limits>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "models/core/enum_names.h"

namespace waam::models {

// What the parameters drive: fe (inherent strain, linear elastic FE) or reduced (layer shrinkage + axis bending).
enum class DistortionMode { kFe, kReduced };
constexpr std::array<EnumName<DistortionMode>, 2> EnumNames(DistortionMode) {
  return {{{DistortionMode::kFe, "fe"}, {DistortionMode::kReduced, "reduced"}}};
}
WAAM_ENUM_JSON(DistortionMode)
// The mode named `name`; throws InputError "<where> = 'name': must be one of fe, reduced" for another name.
DistortionMode ParseDistortionMode(const std::string& name, const std::string& where);

// The fitted distortion parameters (model file models/data/distortion.json). The inherent strain of a deposited
// voxel is eps(q) = strain x (q / reference_heat_input)^heat_exponent, q = heat input per length of its bead.
struct DistortionParams {
  double strain = 0.004;                 // in-layer shrinkage strain at the reference heat input, 1 (> 0 shrinks)
  double vertical_ratio = 0.5;           // build-direction strain / in-layer strain, 1
  double heat_exponent = 0.5;            // n of (q / q_ref)^n, 1
  double reference_heat_input_j_mm = 240.0;  // q_ref, J/mm (CMT, 1.0 mm steel wire 3.2 m/min at 400 mm/min)
  double arc_energy_per_wire_j_mm = 30.0;    // arc energy per mm of wire fed (synergic line), J/mm
  double substrate_stiffness_n_mm3 = 2000.0; // Winkler modulus of the clamped substrate under the part, N/mm^3
  double youngs_modulus_mpa = 200000.0;  // E of the deposited metal at room temperature, MPa
  double poisson = 0.3;                  // nu, 1
  DistortionMode mode = DistortionMode::kFe;  // model the parameters were fitted for
  // The thermal law (used only when a thermal history is given, docs/compensation.md "Heat into shape"):
  // temperature above which the metal carries no stress (mechanical melting), degC. 800 degC: EN 1993-1-2 Table 3.1
  // leaves carbon steel 11 % of its yield strength there (k_y = 0.11).
  double mechanical_melting_c = 800.0;
  // Interpass temperature the strains were fitted at, degC; NaN = not recorded (the caller supplies the build's).
  double reference_interpass_c = std::numeric_limits<double>::quiet_NaN();

  // Heat input per length of a bead laid at `speed_mm_s` with wire feed `wire_feed_mm_s` (both > 0), J/mm.
  double HeatInput(double wire_feed_mm_s, double speed_mm_s) const;
  // In-layer inherent strain at heat input `q_j_mm` (> 0), 1.
  double StrainAt(double q_j_mm) const;
  // Factor on StrainAt for metal that peaked at `peak_c` and was laid on metal at `interpass_c` (degC):
  // (min(T_peak, T_mm) - T_ip) / (T_mm - T_ref), at least 0; exactly 1 at T_ip = T_ref with T_peak >= T_mm.
  // reference_interpass_c must be finite and below mechanical_melting_c (WAAM_DEMAND).
  double ThermalFactor(double peak_c, double interpass_c) const;
};

// The parameters a fit of the distortion model may free, by their names in the model file.
enum class DistortionParam { kStrain, kHeatExponent, kVerticalRatio, kSubstrateStiffness };
constexpr std::array<EnumName<DistortionParam>, 4> EnumNames(DistortionParam) {
  return {{{DistortionParam::kStrain, "strain"},
           {DistortionParam::kHeatExponent, "heat_exponent"},
           {DistortionParam::kVerticalRatio, "vertical_ratio"},
           {DistortionParam::kSubstrateStiffness, "substrate_stiffness_n_mm3"}}};
}
WAAM_ENUM_JSON(DistortionParam)
// The parameter named `name`; throws InputError "<where> '<name>': must be one of strain, ..." for another name.
DistortionParam ParseDistortionParam(const std::string& name, const std::string& where);
// The member of `params` that `param` names.
double& ParamValue(DistortionParams& params, DistortionParam param);
double ParamValue(const DistortionParams& params, DistortionParam param);

// The first parameter of `params` outside its valid range, as "<where>: <name> = <value>: must be in [lo, hi]",
// or "" when all are valid. Does not throw (the distortion fit asks it at every trial step).
std::string DistortionParamsProblem(const DistortionParams& params, const std::string& where);

// Throws InputError "<where>: <field> = value: must be ..." for a parameter out of its range.
void ValidateDistortionParams(const DistortionParams& params, const std::string& where);

// The model file (format of models/fit/model_file.h, "model": "distortion"); `fit` (may be null) is stored as is.
nlohmann::json DistortionParamsToJson(const DistortionParams& params, const nlohmann::json* fit = nullptr);
// Reads and validates a distortion model file. Throws InputError naming the file and the field.
DistortionParams ReadDistortionParams(const std::filesystem::path& path);

}  // namespace waam::models
