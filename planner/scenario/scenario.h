// The planner's sections of a scenario: the part, how to slice it, which path pattern, which process settings, and
// the data they name (the part's STL bytes, the fitted models), loaded by the scenario loader (analysis/scenario.h).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "models/bead/csw_model.h"
#include "models/bead/speed_height_model.h"
#include "models/bead/width_height_model.h"
#include "models/core/enum_names.h"
#include "planner/mesh/generators.h"
#include "planner/path/pattern_names.h"
#include "planner/scenario/arc_settings.h"
#include "planner/scenario/void_filling_settings.h"

namespace waam::planner {

// The closed sets of names of the scenario's slicing and process sections (models/core/enum_names.h).
// slicing.type
enum class SlicingType { kPlanar, kCone, kCylinder, kMultiDirectional, kSkeleton };
constexpr std::array<EnumName<SlicingType>, 5> EnumNames(SlicingType) {
  return {{{SlicingType::kPlanar, "planar"}, {SlicingType::kCone, "cone"}, {SlicingType::kCylinder, "cylinder"},
           {SlicingType::kMultiDirectional, "multi_directional"}, {SlicingType::kSkeleton, "skeleton"}}};
}
WAAM_ENUM_JSON(SlicingType)
// slicing.split (multi_directional)
enum class SplitMethod { kPlanes, kCentroidShift };
constexpr std::array<EnumName<SplitMethod>, 2> EnumNames(SplitMethod) {
  return {{{SplitMethod::kPlanes, "planes"}, {SplitMethod::kCentroidShift, "centroid_shift"}}};
}
WAAM_ENUM_JSON(SplitMethod)
// process.bead_model
enum class BeadModel { kVolumeBalance, kSpeedHeight, kCsw };
constexpr std::array<EnumName<BeadModel>, 3> EnumNames(BeadModel) {
  return {{{BeadModel::kVolumeBalance, "volume_balance"}, {BeadModel::kSpeedHeight, "speed_height"},
           {BeadModel::kCsw, "csw"}}};
}
WAAM_ENUM_JSON(BeadModel)

// Where the part comes from: an STL file or a procedural generator with parameters.
struct PartSpec {
  std::filesystem::path mesh_path;   // absolute, resolved against the scenario file's folder; empty for a generator
  std::optional<PartGenerator> generator;  // the generator (planner/mesh/generators.h); empty for a mesh
  std::map<std::string, std::vector<double>> params;  // generator parameters, each a number or list of numbers
  std::string where;                 // "file:line: part" for messages about the part
  std::string mesh_where;            // "file:line: part.mesh" for messages about the mesh file; empty for a generator
  // The bytes of the mesh file, read by the scenario loader (the planner reads no file); null for a generator.
  std::shared_ptr<const std::string> mesh_data;
};

// A sub-volume of a multi-directional decomposition (Lim & Soh): the part's metal inside every `keep` half-space
// n . p <= c (n, then c in mm; user-given split planes), planar-sliced along `direction` (unit after loading).
struct SubVolumeSpec {
  std::string name;
  std::array<double, 3> direction = {0.0, 0.0, 1.0};
  std::vector<std::array<double, 4>> keep;
};

struct SlicingSettings {
  SlicingType type = SlicingType::kPlanar;
  double layer_height_mm = 1.5;      // > 0 (cone, cylinder: normal distance d between equidistant surfaces)
  // cone | cylinder (Dai et al. 2020, planner/cone_planner.h): the first surface x^2 + y^2 = R^2 (z/H - 1)^2
  // about a vertical axis through axis_mm; layer i is its equidistant surface at (i + 1/2) d.
  double cone_R_mm = 60.0;                          // radius at axis_mm, mm
  double cone_H_mm = 200.0;                         // axis_mm to the apex, mm (cone only; < 0: widens upwards)
  std::array<double, 3> cone_axis_mm = {0.0, 0.0, 0.0};  // point on the axis, part frame, mm
  double cone_rotation_step_deg = 11.0;             // rotation step before flattening (Dai sec. 2.2), deg
  std::vector<SubVolumeSpec> sub_volumes;           // multi_directional: built in this order
  // multi_directional: "planes" (the user's sub_volumes) or "centroid_shift" (found by the overhang decomposition of
  // the dissertation, sec. 5.4: planner/slicing/centroid_decomposition.h)
  SplitMethod split = SplitMethod::kPlanes;
  double overhang_deg = 15.0;        // centroid_shift: self-supporting overhang from +z, deg
  // skeleton: adaptive slicing along the central axis (dissertation 6.3.1, Fig. 56; Table 16 limits)
  double h_min_mm = 1.0;             // thinnest depositable layer, mm
  double h_max_mm = 2.0;             // thickest depositable layer, mm
  double point_spacing_mm = 2.0;     // path point spacing along each layer, mm (2 mm in sec. 6.3.3)
  double first_step_mm = 0.0;        // initial moving distance h', mm; 0 = (h_min + h_max) / 2
  double beta_deg = 0.1;             // plane re-orientation threshold on gamma (eq. 5.26), deg
  double wall_mm = 0.0;              // wall of the part for its mid-wall path, mm; 0 = measured on the base section
};

struct PathSettings {
  Pattern pattern = Pattern::kContinuous;  // eulerian: 003 sec. 4.3; spiral: skeleton slicing only
  double bead_width_mm = 6.0;          // > 0
  OverlapModel overlap_model = OverlapModel::kProposed;  // proposed: 0.738 w / 0.47 w / 0.5 w; existing: 0.738 w
  bool zigzag_angle_auto = true;       // minimum-width direction (Ding Lemma 1)
  double zigzag_angle_deg = 0.0;       // used when not auto
  bool alternate_start = true;         // shift the start point layer to layer so starts do not stack
  std::uint64_t seed = 1;              // for any random choice in planning
  double retract_mm = 15.0;            // >= 0: arc-off lift / approach along the torch axis, and the travel's
                                       // clearance over the metal (planner/path/retract.h); 0 = straight rapids
  VoidFillingSettings void_filling;    // optional `void_filling:` junction correction (003 sec. 4.4)
  // The order of the islands (or passes) of each layer: as planned, round robin (each layer starts at the next
  // island), or the island whose last deposition is longest ago first (planner/timeline/island_order.h)
  IslandOrder island_order = IslandOrder::kAsPlanned;
};


struct ProcessSettings {
  double travel_speed_mm_min = 400.0;  // welding travel speed
  double wire_feed_mm_min = 3200.0;    // wire feed speed
  double wire_diameter_mm = 1.0;
  double deposition_efficiency = 1.0;  // share of the wire volume that lands in the bead (eq. 3.4), (0, 1]
  // Where the bead comes from: "volume_balance" (travel speed and bead width as given, height from eq. 3.4) or
  // "speed_height" (speed for the layer height and the width that comes with it, from the fitted speed-height and
  // width-height models, dissertation sec. 6.3.2.1; path.bead_width_mm and travel_speed_mm_min are then ignored).
  // "csw" (cone/cylinder slicing only): speed per point from the path curvature with the CSW model of Dai et al.
  // for the bead width path.bead_width_mm, height from eq. 3.4.
  BeadModel bead_model = BeadModel::kVolumeBalance;
  std::filesystem::path csw_model;           // model JSON (waam fit csw); empty = models/data default
  std::filesystem::path speed_height_model;  // model JSON (waam fit speed-height); empty = models/data default
  std::filesystem::path width_height_model;  // model JSON (waam fit width-height); empty = models/data default
  // The three models above (the named files or the defaults), loaded by the scenario loader; the planners take them
  // from here (one they need and do not find is the caller's mistake: WAAM_DEMAND).
  std::shared_ptr<const models::CswModel> csw;
  std::shared_ptr<const models::SpeedHeightModel> speed_height;
  std::shared_ptr<const models::WidthHeightModel> width_height;
  double rapid_speed_mm_min = 6000.0;  // arc-off travel moves
  // Arc start (gas pre-flow, ignition) before each pass and arc end (crater fill, arc off) after it, s; defaults and
  // their source in docs/TIMELINE.md (Kemppi's start/stop timing with typical gas pre-flow and crater times).
  double arc_start_s = 0.5;
  double arc_end_s = 0.3;
  // Curvature radii below this count as this in the CSW speed choice (bead_model csw): the smallest radius the CSW
  // model was fitted to. Its key is the twin's simulation.csw_min_radius_mm (the twin widens beads by the same rule);
  // the full scenario loader (analysis/scenario.h) copies it here.
  double csw_min_radius_mm = 30.0;
  ArcSettings arc;                      // process.arc: arc power and efficiency (the thermal model's heat input)
  InterpassSettings interpass;          // process.interpass: wait before a layer for a temperature or a layer time
};

// What the planner reads of a scenario. The one scenario type, analysis::Scenario, holds these sections with those
// of the twin and the analysis, and is passed to the planner as this.
struct PlannerSections {
  std::filesystem::path file;        // the scenario file (absolute)
  // The folder relative file paths of the scenario are resolved against (absolute): the top-level `base_dir` (itself
  // relative to the file's folder), or the file's folder. A scenario written elsewhere (`waam place`) keeps pointing
  // at its original meshes and models this way.
  std::filesystem::path dir;
  std::string base_dir_where;        // "file:line: base_dir" when the scenario gives one (the loader checks the folder)
  std::string name;
  PartSpec part;
  SlicingSettings slicing;
  PathSettings path;
  ProcessSettings process;
};

}  // namespace waam::planner
