// Settings of the voxel deposition twin (scenario section `simulation`), owned by the twin: voxel size, corner
// blending, arc start/stop, their names and ranges, and the section's parser.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

#include "models/bead/csw_model.h"
#include "models/core/enum_names.h"
#include "models/core/field_table.h"

namespace waam::twin {

// simulation.blend
enum class Blend { kNone, kFixed, kSpeed };
constexpr std::array<EnumName<Blend>, 3> EnumNames(Blend) {
  return {{{Blend::kNone, "none"}, {Blend::kFixed, "fixed"}, {Blend::kSpeed, "speed"}}};
}
WAAM_ENUM_JSON(Blend)
// simulation.stop_crater
enum class StopCrater { kLip, kLost };
constexpr std::array<EnumName<StopCrater>, 2> EnumNames(StopCrater) {
  return {{{StopCrater::kLip, "lip"}, {StopCrater::kLost, "lost"}}};
}
WAAM_ENUM_JSON(StopCrater)
// simulation.start_wetting
enum class StartWetting { kCold, kHot };
constexpr std::array<EnumName<StartWetting>, 2> EnumNames(StartWetting) {
  return {{{StartWetting::kCold, "cold"}, {StartWetting::kHot, "hot"}}};
}
WAAM_ENUM_JSON(StartWetting)
// simulation.curvature_width
enum class CurvatureWidth { kCsw, kNone };
constexpr std::array<EnumName<CurvatureWidth>, 2> EnumNames(CurvatureWidth) {
  return {{{CurvatureWidth::kCsw, "csw"}, {CurvatureWidth::kNone, "none"}}};
}
WAAM_ENUM_JSON(CurvatureWidth)

struct SimulationSettings {
  double voxel_mm = 0.5;                 // voxel edge, mm, in [0.1, 2]
  std::size_t max_voxels = 400000000;    // refuse to occupy more voxels than this (about 8.5 bytes each)

  // Corner blending of the executed path, like a robot's continuous-motion mode (FANUC CNT100, 003 sec. 4.4.1):
  // none = the TCP reaches every vertex (FINE); fixed = blend radius blend_radius_mm;
  // speed = blend radius travel speed x blend_time_s (a faster torch cuts corners more).
  Blend blend = Blend::kSpeed;
  double blend_radius_mm = 2.0;          // mm, for blend = fixed
  double blend_time_s = 0.3;             // s, for blend = speed

  // Arc start and stop (Ding et al. Fig. 1): over the first start_length_mm of a pass the bead is taller and narrower
  // (cold start, humping); over the last stop_length_mm it shrinks (crater at the arc end).
  double start_length_mm = 8.0;          // mm
  double start_height_factor = 1.25;     // x planned bead height at the very start, blending linearly to 1
  double start_width_factor = 0.85;      // x planned bead width at the very start
  double stop_length_mm = 8.0;           // mm
  double stop_height_factor = 0.6;       // x planned bead height at the very end
  double stop_width_factor = 0.9;        // x planned bead width at the very end
  // Where the crater's missing metal goes (the wire feeds until the arc stops): lip = it froze in the pool's tail,
  // the stop_length_mm of bead before the crater (volume per pass = what the wire brought); lost = nowhere (the
  // pass deposits less than its wire brings).
  StopCrater stop_crater = StopCrater::kLip;
  // hot = the start's metal levels into the valleys under its footprint like the steady pool; cold = it wets the
  // cold base poorly and sets on the ground under it as a draped hump, fading to the levelled pool over
  // start_length_mm (an option, not the default: see docs/deposition_twin.md, "Start and stop").
  StartWetting start_wetting = StartWetting::kHot;

  // Molten metal hanging past a free edge flows down at most (1 + edge_sag_factor) x bead height below its crown.
  double edge_sag_factor = 2.0;
  // Molten metal wets lower ground next to the bead: the parabolic cap continues past w/2 up to
  // (0.5 + edge_spread_factor) x w from the path, filling only where the ground lies below it (a free side).
  double edge_spread_factor = 0.15;
  // Bead width on curved paths (Dai et al. CSW model): csw = wider and lower on curves by the model's curvature term,
  // none = the planned width everywhere. csw_model: a model file from `waam fit csw` (empty = models/data/csw.json);
  // radii below csw_min_radius_mm (the smallest radius the model was fitted to) are clamped to it, here and in the
  // cone planner's CSW speed choice (process.bead_model: csw).
  CurvatureWidth curvature_width = CurvatureWidth::kCsw;
  std::filesystem::path csw_model;
  double csw_min_radius_mm = 30.0;
  // The model of csw_model (or the default), loaded by the scenario loader (analysis::LoadScenario; the twin reads no
  // file); needed when curvature_width is csw.
  std::shared_ptr<const models::CswModel> csw;
  // Deposition step along the path, mm (0 = one voxel).
  double step_mm = 0.0;
  // Voids and valleys smaller than this are voxel-scale gaps between beads, counted apart from the voids (mm3; the
  // default is a 1 mm cube, eight voxels at 0.5 mm, well below the millimetre voids that milled sections show).
  double min_void_volume_mm3 = 1.0;
};

// The `simulation:` section, one row per key (models/core/field_table.h).
inline constexpr std::array kSimulationFields = {
    NumField<&SimulationSettings::voxel_mm>("voxel_mm", "mm", 0.1, 2.0, "voxel edge"),
    NumField<&SimulationSettings::max_voxels>("max_voxels", "", 1000.0, 2.0e9,
                                         "refuse to occupy more voxels than this (about 8.5 bytes each)"),
    OptField<&SimulationSettings::blend>("blend", "corner blending of the executed path (FANUC CNT): none = FINE"),
    NumField<&SimulationSettings::blend_radius_mm>("blend_radius_mm", "mm", 0.0, 100.0, "blend radius for blend fixed"),
    NumField<&SimulationSettings::blend_time_s>("blend_time_s", "s", 0.0, 10.0,
                                           "blend radius = travel speed x this, for blend speed"),
    NumField<&SimulationSettings::start_length_mm>("start_length_mm", "mm", 0.0, 200.0, "length of the arc start"),
    NumField<&SimulationSettings::start_height_factor>("start_height_factor", "", 0.2, 3.0,
                                                  "x planned bead height at the very start"),
    NumField<&SimulationSettings::start_width_factor>("start_width_factor", "", 0.2, 3.0,
                                                 "x planned bead width at the very start"),
    NumField<&SimulationSettings::stop_length_mm>("stop_length_mm", "mm", 0.0, 200.0, "length of the arc stop"),
    NumField<&SimulationSettings::stop_height_factor>("stop_height_factor", "", 0.2, 3.0,
                                                 "x planned bead height at the very end"),
    NumField<&SimulationSettings::stop_width_factor>("stop_width_factor", "", 0.2, 3.0,
                                                "x planned bead width at the very end"),
    OptField<&SimulationSettings::stop_crater>("stop_crater", "where the crater's metal goes: lip = the pool's tail"),
    OptField<&SimulationSettings::start_wetting>("start_wetting", "hot = levels like the pool; cold = a draped hump"),
    NumField<&SimulationSettings::edge_sag_factor>("edge_sag_factor", "", 0.0, 10.0,
                                              "metal past a free edge sags at most (1 + this) x bead height"),
    NumField<&SimulationSettings::edge_spread_factor>("edge_spread_factor", "", 0.0, 1.0,
                                                 "metal wets lower ground up to (0.5 + this) x w from the path"),
    OptField<&SimulationSettings::curvature_width>("curvature_width", "csw = wider, lower beads on curves (Dai et al.)"),
    FileField<&SimulationSettings::csw_model>("csw_model", "model file", "CSW model JSON (waam fit csw); absent = the default"),
    NumField<&SimulationSettings::csw_min_radius_mm>("csw_min_radius_mm", "mm", 1.0, 10000.0,
                                                "radii below this count as this (the CSW fit's smallest)"),
    NumField<&SimulationSettings::step_mm>("step_mm", "mm", 0.0, 10.0, "deposition step along the path; 0 = one voxel"),
    NumField<&SimulationSettings::min_void_volume_mm3>("min_void_volume_mm3", "mm3", 0.0, 1.0e6,
                                                  "smaller voids count as voxel-scale gaps"),
};

// Throws InputError "simulation.<key> = value: must be in [min, max]" for a setting outside its range.
void ValidateSimulationSettings(const SimulationSettings& settings);

// Reads the optional `simulation:` mapping of the scenario's top level into `out` (defaults where a key is absent);
// a relative csw_model path is taken from top.base_dir() (the scenario's folder; the loader checks the file).
// Throws InputError naming file, line and key for unknown keys and out-of-range values.
void ParseSimulationSection(YamlMap& top, SimulationSettings* out);

}  // namespace waam::twin
