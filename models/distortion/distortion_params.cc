// Distortion parameters: heat input per length, inherent strain law, validation and the model file.
#include "models/distortion/distortion_params.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "models/core/error.h"
#include "models/fit/model_file.h"

namespace waam::models {

double DistortionParams::HeatInput(double wire_feed_mm_s, double speed_mm_s) const {
  WAAM_THROW_UNLESS(wire_feed_mm_s > 0.0 && speed_mm_s > 0.0,
                    "distortion: wire feed " << wire_feed_mm_s << " mm/s and travel speed " << speed_mm_s
                                             << " mm/s: both must be > 0");
  // Heat input per length q = P / v with the arc power on the synergic line P = e_w * v_w (CMT: the power follows
  // the wire feed, dissertation sec. 6.3.2.1). At a fixed wire feed a slower, thicker segment gets more heat.
  return arc_energy_per_wire_j_mm * wire_feed_mm_s / speed_mm_s;
}

double DistortionParams::StrainAt(double q_j_mm) const {
  return strain * std::pow(std::max(q_j_mm, 1e-9) / reference_heat_input_j_mm, heat_exponent);
}

double DistortionParams::ThermalFactor(double peak_c, double interpass_c) const {
  WAAM_DEMAND(std::isfinite(reference_interpass_c) && reference_interpass_c < mechanical_melting_c);
  // Inherent strain as the thermal strain a restrained fibre keeps (Ueda's inherent strain; Murakawa, Luo, Ueda
  // 1996, J. Soc. Nav. Archit. Jpn 180, 739): alpha (min(T_peak, T_mm) - T_0), where T_0 is the temperature it
  // cools back to before the next layer restrains it (its interpass temperature) and T_mm caps what a hot, soft fibre
  // can hold. The fitted strain fixes alpha at the reference history, so only the ratio enters.
  const double effective_peak = std::min(peak_c, mechanical_melting_c);
  return std::max(0.0, effective_peak - interpass_c) / (mechanical_melting_c - reference_interpass_c);
}

std::string DistortionParamsProblem(const DistortionParams& p, const std::string& where) {
  std::ostringstream problem;
  auto range = [&](const char* name, double v, double lo, double hi) {
    if (problem.tellp() > 0 || (std::isfinite(v) && v >= lo && v <= hi)) return;
    problem << where << ": " << name << " = " << v << ": must be in [" << lo << ", " << hi << "]";
  };
  range("strain", p.strain, 0.0, 0.1);
  range("vertical_ratio", p.vertical_ratio, 0.0, 10.0);
  range("heat_exponent", p.heat_exponent, -3.0, 3.0);
  range("reference_heat_input_j_mm", p.reference_heat_input_j_mm, 1e-3, 1e5);
  range("arc_energy_per_wire_j_mm", p.arc_energy_per_wire_j_mm, 1e-3, 1e4);
  range("substrate_stiffness_n_mm3", p.substrate_stiffness_n_mm3, 1e-3, 1e9);
  range("youngs_modulus_mpa", p.youngs_modulus_mpa, 1.0, 1e7);
  range("poisson", p.poisson, 0.0, 0.49);
  range("mechanical_melting_c", p.mechanical_melting_c, 100.0, 3000.0);
  if (!std::isnan(p.reference_interpass_c)) {
    range("reference_interpass_c", p.reference_interpass_c, -50.0, p.mechanical_melting_c - 1.0);
  }
  return problem.str();
}

void ValidateDistortionParams(const DistortionParams& p, const std::string& where) {
  const std::string problem = DistortionParamsProblem(p, where);
  WAAM_THROW_UNLESS(problem.empty(), problem);
}

DistortionMode ParseDistortionMode(const std::string& name, const std::string& where) {
  const std::optional<DistortionMode> mode = ParseEnum<DistortionMode>(name);
  WAAM_THROW_UNLESS(mode.has_value(),
                    where << " = '" << name << "': must be one of " << EnumNameList<DistortionMode>());
  return *mode;
}

DistortionParam ParseDistortionParam(const std::string& name, const std::string& where) {
  const std::optional<DistortionParam> param = ParseEnum<DistortionParam>(name);
  WAAM_THROW_UNLESS(param.has_value(),
                    where << " '" << name << "': must be one of " << EnumNameList<DistortionParam>());
  return *param;
}

double& ParamValue(DistortionParams& params, DistortionParam param) {
  switch (param) {
    case DistortionParam::kStrain: return params.strain;
    case DistortionParam::kHeatExponent: return params.heat_exponent;
    case DistortionParam::kVerticalRatio: return params.vertical_ratio;
    case DistortionParam::kSubstrateStiffness: return params.substrate_stiffness_n_mm3;
  }
  WAAM_DEMAND(false);
  return params.strain;
}

double ParamValue(const DistortionParams& params, DistortionParam param) {
  return ParamValue(const_cast<DistortionParams&>(params), param);
}

nlohmann::json DistortionParamsToJson(const DistortionParams& p, const nlohmann::json* fit) {
  nlohmann::json j = {
      {"model", "distortion"},
      {"format_version", kModelFormatVersion},
      {"formula", "eps(q) = strain * (q / reference_heat_input_j_mm)^heat_exponent, q = e_w * v_wire / v_travel"},
      {"source", "inherent-strain method (waam-twin); compensation after Nguyen 2022 dissertation sec. 6.5.2"},
      {"mode", p.mode},
      {"params",
       {{"strain", p.strain},
        {"vertical_ratio", p.vertical_ratio},
        {"heat_exponent", p.heat_exponent},
        {"reference_heat_input_j_mm", p.reference_heat_input_j_mm},
        {"arc_energy_per_wire_j_mm", p.arc_energy_per_wire_j_mm},
        {"substrate_stiffness_n_mm3", p.substrate_stiffness_n_mm3},
        {"youngs_modulus_mpa", p.youngs_modulus_mpa},
        {"poisson", p.poisson},
        {"mechanical_melting_c", p.mechanical_melting_c}}},
      {"units",
       {{"strain", "1"},
        {"vertical_ratio", "1"},
        {"heat_exponent", "1"},
        {"reference_heat_input_j_mm", "J/mm"},
        {"arc_energy_per_wire_j_mm", "J/mm of wire"},
        {"substrate_stiffness_n_mm3", "N/mm^3"},
        {"youngs_modulus_mpa", "MPa"},
        {"poisson", "1"},
        {"mechanical_melting_c", "degC"},
        {"reference_interpass_c", "degC"}}},
  };
  if (!std::isnan(p.reference_interpass_c)) j["params"]["reference_interpass_c"] = p.reference_interpass_c;
  if (fit != nullptr) j["fit"] = *fit;
  return j;
}

DistortionParams ReadDistortionParams(const std::filesystem::path& path) {
  const nlohmann::json j = ReadModelJson(path, "distortion");
  const std::string where = path.string();
  DistortionParams p;
  p.strain = JsonNumber(j, "/params/strain", where);
  p.vertical_ratio = JsonNumber(j, "/params/vertical_ratio", where);
  p.heat_exponent = JsonNumber(j, "/params/heat_exponent", where);
  p.reference_heat_input_j_mm = JsonNumber(j, "/params/reference_heat_input_j_mm", where);
  p.arc_energy_per_wire_j_mm = JsonNumber(j, "/params/arc_energy_per_wire_j_mm", where);
  p.substrate_stiffness_n_mm3 = JsonNumber(j, "/params/substrate_stiffness_n_mm3", where);
  p.youngs_modulus_mpa = JsonNumber(j, "/params/youngs_modulus_mpa", where);
  p.poisson = JsonNumber(j, "/params/poisson", where);
  // The thermal law's two parameters are optional (files written before it keep their meaning).
  if (j.contains(nlohmann::json::json_pointer("/params/mechanical_melting_c"))) {
    p.mechanical_melting_c = JsonNumber(j, "/params/mechanical_melting_c", where);
  }
  if (j.contains(nlohmann::json::json_pointer("/params/reference_interpass_c"))) {
    p.reference_interpass_c = JsonNumber(j, "/params/reference_interpass_c", where);
  }
  WAAM_THROW_UNLESS(j.contains("mode") && j["mode"].is_string(), where << ": mode is missing or not a string");
  p.mode = ParseDistortionMode(j["mode"].get<std::string>(), where + ": mode");
  ValidateDistortionParams(p, where);
  return p;
}

}  // namespace waam::models
