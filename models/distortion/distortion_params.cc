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

namespace {

// One row per parameter of the model file: its key, member, unit and valid range. reference_interpass_c may be
// NaN (not set: the thermal law is off), and its range ends 1 degC below mechanical_melting_c; the two thermal
// parameters may be absent from a file (files written before the thermal law keep their meaning).
struct ParamField {
  const char* key;
  double DistortionParams::*member;
  const char* unit;
  double lo;
  double hi;
  bool optional;
};

constexpr ParamField kParamFields[] = {
    {"strain", &DistortionParams::strain, "1", 0.0, 0.1, false},
    {"vertical_ratio", &DistortionParams::vertical_ratio, "1", 0.0, 10.0, false},
    {"heat_exponent", &DistortionParams::heat_exponent, "1", -3.0, 3.0, false},
    {"reference_heat_input_j_mm", &DistortionParams::reference_heat_input_j_mm, "J/mm", 1e-3, 1e5, false},
    {"arc_energy_per_wire_j_mm", &DistortionParams::arc_energy_per_wire_j_mm, "J/mm of wire", 1e-3, 1e4, false},
    {"substrate_stiffness_n_mm3", &DistortionParams::substrate_stiffness_n_mm3, "N/mm^3", 1e-3, 1e9, false},
    {"youngs_modulus_mpa", &DistortionParams::youngs_modulus_mpa, "MPa", 1.0, 1e7, false},
    {"poisson", &DistortionParams::poisson, "1", 0.0, 0.49, false},
    {"mechanical_melting_c", &DistortionParams::mechanical_melting_c, "degC", 100.0, 3000.0, true},
    {"reference_interpass_c", &DistortionParams::reference_interpass_c, "degC", -50.0, 0.0, true},
};

bool IsInterpass(const ParamField& f) { return f.member == &DistortionParams::reference_interpass_c; }

}  // namespace

std::string DistortionParamsProblem(const DistortionParams& p, const std::string& where) {
  for (const ParamField& f : kParamFields) {
    const double v = p.*f.member;
    if (IsInterpass(f) && std::isnan(v)) continue;
    const double hi = IsInterpass(f) ? p.mechanical_melting_c - 1.0 : f.hi;
    if (std::isfinite(v) && v >= f.lo && v <= hi) continue;
    std::ostringstream problem;
    problem << where << ": " << f.key << " = " << v << ": must be in [" << f.lo << ", " << hi << "]";
    return problem.str();
  }
  return "";
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
  };
  j["params"] = nlohmann::json::object();
  j["units"] = nlohmann::json::object();
  for (const ParamField& f : kParamFields) {
    j["units"][f.key] = f.unit;
    if (!(IsInterpass(f) && std::isnan(p.*f.member))) j["params"][f.key] = p.*f.member;
  }
  if (fit != nullptr) j["fit"] = *fit;
  return j;
}

DistortionParams ReadDistortionParams(const std::filesystem::path& path) {
  const nlohmann::json j = ReadModelJson(path, "distortion");
  const std::string where = path.string();
  DistortionParams p;
  for (const ParamField& f : kParamFields) {
    const std::string pointer = std::string("/params/") + f.key;
    if (f.optional && !j.contains(nlohmann::json::json_pointer(pointer))) continue;  // the default stays
    p.*f.member = JsonNumber(j, pointer, where);
  }
  WAAM_THROW_UNLESS(j.contains("mode") && j["mode"].is_string(), where << ": mode is missing or not a string");
  p.mode = ParseDistortionMode(j["mode"].get<std::string>(), where + ": mode");
  ValidateDistortionParams(p, where);
  return p;
}

}  // namespace waam::models
