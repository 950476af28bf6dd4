// The planner's scenario sections (part, slicing, path, path.void_filling, process, program), one row per key
// (models/core/field_table.h): read by planner/scenario/scenario.cc, documented in docs/SCENARIO_KEYS.md.
#pragma once

#include <array>

#include "models/core/field_table.h"
#include "planner/program/program_settings.h"
#include "planner/scenario/scenario.h"

namespace waam::planner {

inline constexpr std::array kScenarioTopFields = {
    OptField<&PlannerSections::name>("name", "the scenario's name (output folders, reports); required"),
    CustomField<PlannerSections>("base_dir", FieldType::kString, "folder relative paths are taken from; absent: the file's"),
    CustomField<PlannerSections>("part", FieldType::kMap, "the part to plan (or program:, a program made elsewhere)"),
};

inline constexpr std::array kPartFields = {
    FileField<&PartSpec::mesh_path>("mesh", "mesh file", "an STL file"),
    CustomField<PartSpec>("generator", FieldType::kMap, "type: a generator (waam generate --help), then its parameters"),
};
// part.generator's own key; each type's parameters are its table (planner/mesh/generators.h: GeneratorFields).
inline constexpr std::array kPartGeneratorFields = {
    OptField<&PartSpec::generator>("type", "the generator (required); its parameters below", "", "generator type"),
};

// Finishes a sub-volume read from `element` (slicing.sub_volumes[i]): name and direction are required, the direction
// must not be zero and is made unit. Throws InputError naming the element's key.
void FinishSubVolume(YamlMap& element, SubVolumeSpec* sub);

inline constexpr std::array kSubVolumeFields = {
    OptField<&SubVolumeSpec::name>("name", "the sub-volume's name (required)"),
    NumField<&SubVolumeSpec::direction>("direction", "", -1e3, 1e3, "build direction (required), not zero; made unit"),
    NumField<&SubVolumeSpec::keep>("keep", "mm", -1e6, 1e6,
                                   "half-spaces n . p <= c, 4 numbers each (nx, ny, nz, c mm); absent: none"),
};

inline constexpr std::array kSlicingFields = {
    OptField<&SlicingSettings::type>("type", "how the part is cut into layers"),
    NumField<&SlicingSettings::layer_height_mm>("layer_height_mm", "mm", 0.05, 20.0,
                                           "layer height (cone, cylinder: surface distance); required but skeleton"),
    NumField<&SlicingSettings::cone_R_mm>("R_mm", "mm", 0.1, 1e5, "cone, cylinder (required): radius at axis_mm"),
    NumField<&SlicingSettings::cone_H_mm>("H_mm", "mm", -1e6, 1e6, "cone (required): axis_mm to apex, at least 1 in size"),
    NumField<&SlicingSettings::cone_axis_mm>("axis_mm", "mm", -1e5, 1e5, "cone, cylinder: point on the axis"),
    NumField<&SlicingSettings::cone_rotation_step_deg>("rotation_step_deg", "deg", 1.0, 180.0,
                                                  "cone, cylinder: rotation step before flattening"),
    OptField<&SlicingSettings::split>("split", "multi_directional: the user's sub_volumes or the overhang split"),
    ListField<&SlicingSettings::sub_volumes, kSubVolumeFields, &FinishSubVolume>(
        "sub_volumes", "multi_directional, split planes: the sub-volumes in build order (slicing.sub_volumes[])"),
    NumField<&SlicingSettings::overhang_deg>("overhang_deg", "deg", 1.0, 80.0, "centroid_shift: self-supporting overhang"),
    NumField<&SlicingSettings::h_min_mm>("h_min_mm", "mm", 0.05, 20.0, "skeleton: thinnest layer"),
    NumField<&SlicingSettings::h_max_mm>("h_max_mm", "mm", 0.05, 20.0, "skeleton: thickest layer, >= h_min_mm"),
    NumField<&SlicingSettings::point_spacing_mm>("point_spacing_mm", "mm", 0.1, 100.0, "skeleton: path point spacing"),
    NumField<&SlicingSettings::first_step_mm>("first_step_mm", "mm", 0.0, 20.0,
                                         "skeleton: initial moving distance; 0 = (h_min + h_max) / 2"),
    NumField<&SlicingSettings::beta_deg>("beta_deg", "deg", 1e-4, 10.0, "skeleton: plane re-orientation threshold"),
    NumField<&SlicingSettings::wall_mm>("wall_mm", "mm", 0.0, 100.0, "skeleton: wall width; 0 = measured"),
};

inline constexpr std::array kPathFields = {
    OptField<&PathSettings::pattern>("pattern", "the path pattern of each layer (required)"),
    NumField<&PathSettings::bead_width_mm>("bead_width_mm", "mm", 0.5, 50.0, "bead width; required but skeleton"),
    OptField<&PathSettings::overlap_model>("overlap_model", "bead spacing: proposed 0.738 w / 0.47 w / 0.5 w"),
    NumField<&PathSettings::zigzag_angle_deg>("zigzag_angle_deg", "deg", -360.0, 360.0,
                                         "zigzag direction, or auto (default): the minimum-width direction"),
    OptField<&PathSettings::alternate_start>("alternate_start", "shift the start point layer to layer"),
    NumField<&PathSettings::seed>("seed", "", 0, 2147483647, "seed of any random choice in planning"),
    NumField<&PathSettings::retract_mm>("retract_mm", "mm", 0.0, 500.0, "arc-off lift and travel clearance; 0 = rapids"),
    OptField<&PathSettings::island_order>("island_order", "order of a layer's islands: as planned, round robin or coolest first"),
    CustomField<PathSettings>("void_filling", FieldType::kMap, "junction void correction (path.void_filling)"),
};

inline constexpr std::array kVoidFillingFields = {
    OptField<&VoidFillingSettings::mode>("mode", "fixed: lambda; model: void-length model; tuned: tune_file"),
    NumField<&VoidFillingSettings::lambda>("lambda", "", 0.0, 100.0, "weight of eq. 4.5 for mode fixed"),
    NumField<&VoidFillingSettings::spacing_mm>("spacing_mm", "mm", 0.0, 100.0, "bead centre distance; 0 = overlap d2"),
    NumField<&VoidFillingSettings::min_ribs>("min_ribs", "", 2, 12, "correct junctions of at least this many ribs"),
    FileField<&VoidFillingSettings::model>("model", "model file", "void-length model JSON (mode model)"),
    FileField<&VoidFillingSettings::tune_file>("tune_file", "tune file", "tune.json of waam tune-voids (mode tuned)"),
};

inline constexpr std::array kProcessFields = {
    NumField<&ProcessSettings::travel_speed_mm_min>("travel_speed_mm_min", "mm/min", 10.0, 10000.0,
                                               "welding travel speed; required but skeleton"),
    NumField<&ProcessSettings::wire_feed_mm_min>("wire_feed_mm_min", "mm/min", 100.0, 30000.0,
                                            "wire feed speed (required)"),
    NumField<&ProcessSettings::wire_diameter_mm>("wire_diameter_mm", "mm", 0.6, 2.4, "wire diameter"),
    NumField<&ProcessSettings::deposition_efficiency>("deposition_efficiency", "", 0.05, 1.0,
                                                 "share of the wire that lands in the bead (eq. 3.4)"),
    OptField<&ProcessSettings::bead_model>("bead_model", "where the bead comes from"),
    FileField<&ProcessSettings::csw_model>("csw_model", "model file", "CSW model JSON (waam fit csw)"),
    FileField<&ProcessSettings::speed_height_model>("speed_height_model", "model file", "speed-height model JSON"),
    FileField<&ProcessSettings::width_height_model>("width_height_model", "model file", "width-height model JSON"),
    NumField<&ProcessSettings::rapid_speed_mm_min>("rapid_speed_mm_min", "mm/min", 100.0, 100000.0, "arc-off travel"),
    NumField<&ProcessSettings::arc_start_s>("arc_start_s", "s", 0.0, 60.0, "ignition before each pass (docs/TIMELINE.md)"),
    NumField<&ProcessSettings::arc_end_s>("arc_end_s", "s", 0.0, 60.0, "crater fill after each pass (docs/TIMELINE.md)"),
    CustomField<ProcessSettings>("arc", FieldType::kMap, "the arc's power and efficiency (docs/THERMAL.md)"),
    CustomField<ProcessSettings>("interpass", FieldType::kMap, "interpass limits: max_c, at, min_layer_time_s"),
};

inline constexpr std::array kProgramFields = {
    FileField<&ProgramSettings::file>("file", "program file", "the program (required)"),
    OptField<&ProgramSettings::format>("format", "the program's dialect; auto: from the extension, then the first lines",
                                       "auto"),
    CustomField<ProgramSettings>("frame", FieldType::kMap, "user_frame_mm: [x, y, z, w, p, r] of the user frame"),
    CustomField<ProgramSettings>("frames", FieldType::kMap, "numbered user frames and tools (program.frames)"),
    OptField<&ProgramSettings::layers>("layers", "how moves are grouped into layers"),
    NumField<&ProgramSettings::layer_tolerance_mm>("layer_tolerance_mm", "mm", 0.0, 1000.0,
                                              "layer grouping tolerance; 0 = half the bead height"),
    CustomField<ProgramSettings>("gcode", FieldType::kMap, "arc signals, feed and dwell units (docs/PROGRAMS.md)"),
    CustomField<ProgramSettings>("yaskawa", FieldType::kMap, "pulses_per_deg [6], station_pulses_per_deg [2]"),
};
// The scenario's top-level `target:` (read with the program section).
inline constexpr std::array kProgramTargetFields = {
    FileField<&ProgramSettings::target>("target", "target file", "the intended part of a program made elsewhere (STL)"),
};
inline constexpr std::array kProgramFrameFields = {
    NumField<&ProgramSettings::user_frame_mm>("user_frame_mm", "mm, deg", -1e6, 1e6,
                                             "[x, y, z, w, p, r] of the user frame; absent: the cell's FANUC world"),
};
inline constexpr std::array kProgramFramesFields = {
    NumberMapField<&ProgramFrames::uframe>("uframe", "frame", 1, 999, "mm, deg", -1e6, 1e6,
                                           "N: [x, y, z, w, p, r] of user frame N (FANUC UFRAME, KUKA BASE_DATA)"),
    NumberMapField<&ProgramFrames::utool>("utool", "tool", 1, 999, "mm, deg", -1e6, 1e6,
                                          "N: [x, y, z, w, p, r] of tool N (FANUC UTOOL, KUKA TOOL_DATA), or torch",
                                          "torch"),
};
inline constexpr std::array kProgramGcodeFields = {
    NumField<&ProgramSettings::gcode_arc_on_m>("arc_on_m", "", 0, 999, "M code that starts the arc"),
    NumField<&ProgramSettings::gcode_arc_off_m>("arc_off_m", "", 0, 999, "M code that stops the arc"),
    WordsField<&ProgramSettings::gcode_arc_on, &CheckGcodeSignal>(
        "arc_on", "signal", 0, "signals that start the arc: [M3], [G82], [M62 P1]...; absent: M<arc_on_m>"),
    WordsField<&ProgramSettings::gcode_arc_off, &CheckGcodeSignal>(
        "arc_off", "signal", 0, "signals that stop the arc: [M5], [G83], [M63 P1]...; absent: M<arc_off_m>"),
    OptField<&ProgramSettings::gcode_feed_unit>("feed_unit", "unit of F"),
    OptField<&ProgramSettings::gcode_dwell_p_unit>("dwell_p_unit", "unit of G4 P"),
};
inline constexpr std::array kProgramYaskawaFields = {
    NumField<&ProgramSettings::yaskawa_pulses_per_deg>(
        "pulses_per_deg", "", 1e-3, 1e7,
        "the arm's encoder pulses per degree, S L U R B T; absent: unknown (not the cell's), a pulse position is "
        "refused unless waam import --pulses-per-deg gives them"),
    NumField<&ProgramSettings::yaskawa_station_pulses_per_deg>(
        "station_pulses_per_deg", "", 1e-3, 1e7,
        "the station's pulses per degree, tilt and rotation; absent: unknown, an EC position or a JBI export is "
        "refused unless --station-pulses-per-deg gives them"),
};

}  // namespace waam::planner
