// Parser of the scenario's `program:` section (planner/program/program_settings.h).
#pragma once

#include <filesystem>

#include "planner/program/program_settings.h"
#include "models/core/yaml_map.h"

namespace waam::planner {

// Reads `program:` from the scenario's top-level map when present (file relative to `scenario_dir`, which must
// exist; format auto or a dialect name; frame.user_frame_mm; frames.uframe.<n> / frames.utool.<n>; layers;
// layer_tolerance_mm; gcode.arc_on_m / arc_off_m / feed_unit; yaskawa.pulses_per_deg,
// yaskawa.station_pulses_per_deg). Throws InputError naming file:line and key.
ProgramSettings ParseProgramSection(YamlMap& top);

}  // namespace waam::planner
