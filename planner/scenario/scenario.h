// A scenario: the part, how to slice it, which path pattern, which process settings (loaded from YAML).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "planner/scenario/cell_settings.h"
#include "planner/scenario/simulation_settings.h"

namespace waam::planner {

// Where the part comes from: an STL file or a procedural generator with parameters.
struct PartSpec {
  std::filesystem::path mesh_path;   // absolute, resolved against the scenario file's folder; empty for a generator
  std::string generator;             // generator name (see planner/mesh/generators.h); empty for a mesh
  std::map<std::string, std::vector<double>> params;  // generator parameters, each a number or list of numbers
  std::string where;                 // "file:line: part" for messages about the part
};

struct SlicingSettings {
  std::string type = "planar";       // planar | skeleton (later: cone, cylinder, multi-directional)
  double layer_height_mm = 1.5;      // > 0 (planar; not used by skeleton)
  // skeleton: adaptive slicing along the central axis (dissertation 6.3.1, Fig. 56; Table 16 limits)
  double h_min_mm = 1.0;             // thinnest depositable layer, mm
  double h_max_mm = 2.0;             // thickest depositable layer, mm
  double point_spacing_mm = 2.0;     // path point spacing along each layer, mm (2 mm in sec. 6.3.3)
  double first_step_mm = 0.0;        // initial moving distance h', mm; 0 = (h_min + h_max) / 2
  double beta_deg = 0.1;             // plane re-orientation threshold on gamma (eq. 5.26), deg
  double wall_mm = 0.0;              // wall of the part for its mid-wall path, mm; 0 = measured on the base section
};

struct PathSettings {
  std::string pattern = "continuous";  // contour | zigzag | hybrid | continuous | spiral (skeleton slicing only)
  double bead_width_mm = 6.0;          // > 0
  std::string overlap_model = "proposed";  // proposed (0.738 w / 0.47 w / 0.5 w) | existing (0.738 w everywhere)
  bool zigzag_angle_auto = true;       // minimum-width direction (Ding Lemma 1)
  double zigzag_angle_deg = 0.0;       // used when not auto
  bool alternate_start = true;         // shift the start point layer to layer so starts do not stack
  std::uint64_t seed = 1;              // for any random choice in planning
};

struct ProcessSettings {
  double travel_speed_mm_min = 400.0;  // welding travel speed
  double wire_feed_mm_min = 3200.0;    // wire feed speed
  double wire_diameter_mm = 1.0;
  double deposition_efficiency = 1.0;  // share of the wire volume that lands in the bead (eq. 3.4), (0, 1]
  // Where the bead comes from: "volume_balance" (travel speed and bead width as given, height from eq. 3.4) or
  // "speed_height" (speed for the layer height and the width that comes with it, from the fitted speed-height and
  // width-height models, dissertation sec. 6.3.2.1; path.bead_width_mm and travel_speed_mm_min are then ignored).
  std::string bead_model = "volume_balance";
  std::filesystem::path speed_height_model;  // model JSON (waam fit speed-height); empty = models/data default
  std::filesystem::path width_height_model;  // model JSON (waam fit width-height); empty = models/data default
  double rapid_speed_mm_min = 6000.0;  // arc-off travel moves
};

struct Scenario {
  std::filesystem::path file;        // the scenario file (absolute)
  std::string name;
  PartSpec part;
  SlicingSettings slicing;
  PathSettings path;
  ProcessSettings process;
  CellSettings cell;                 // optional `cell:` section (planner/scenario/cell_settings.h)
  SimulationSettings simulation;     // optional section `simulation` (voxel twin)
};

// Loads and validates a scenario file. Unknown keys, wrong types and out-of-range values throw InputError naming
// the file, line and key path (e.g. "s.yaml:7: slicing.layer_height_mm = -1: must be in [0.05, 20]").
// `overrides` are "key.path=value" strings (the CLI's --set) applied to the YAML before validation, so a sweep can
// vary one setting without editing the file; a malformed override throws InputError naming it.
Scenario LoadScenario(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

}  // namespace waam::planner
