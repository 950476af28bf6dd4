// The scenario's `program:` section: a robot program or G-code made elsewhere stands in for part/slicing/path.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "models/core/enum_names.h"
#include "planner/program/program_motion.h"
#include "planner/program/program_reader.h"

namespace waam::planner {

// program.layers: how passes group into layers.
enum class ProgramLayers { kAuto };
constexpr std::array<EnumName<ProgramLayers>, 1> EnumNames(ProgramLayers) { return {{{ProgramLayers::kAuto, "auto"}}}; }
WAAM_ENUM_JSON(ProgramLayers)

struct ProgramSettings {
  bool present = false;                       // the scenario has a program: section
  std::filesystem::path file;                 // absolute (given relative to the scenario file)
  std::optional<ProgramFormat> format;        // empty = auto (extension, then first lines)
  // frame.user_frame_mm: where the program's user frame sits in the world, [x, y, z mm, rx, ry, rz deg],
  // R = Rz(rz) Ry(ry) Rx(rx); empty = the cell's FANUC world frame (arm base lifted to the j2 axis).
  std::optional<std::array<double, 6>> user_frame_mm;
  ProgramLayers layers = ProgramLayers::kAuto;
  double layer_tolerance_mm = 0.0;            // >= 0; 0 = half the bead height
  int gcode_arc_on_m = 3;                     // gcode.arc_on_m (when gcode.arc_on is not given)
  int gcode_arc_off_m = 5;                    // gcode.arc_off_m (when gcode.arc_off is not given)
  // gcode.arc_on / arc_off: the signals that switch the arc ("M3", "G82", "M62 P1"); empty = arc_on_m / arc_off_m
  std::vector<std::string> gcode_arc_on, gcode_arc_off;
  GcodeFeedUnit gcode_feed_unit = GcodeFeedUnit::kMmPerMin;  // gcode.feed_unit: mm_per_min | mm_per_s
  GcodeDwellUnit gcode_dwell_p_unit = GcodeDwellUnit::kMs;   // gcode.dwell_p_unit: ms | s
  // frames.uframe.<n> / frames.utool.<n>: frames and tools the program names by number without defining them
  // (FANUC UFRAME / UTOOL, KUKA BASE_DATA / TOOL_DATA), [x, y, z mm, three angles deg]; a tool may be `torch`.
  ProgramFrames frames;
  // yaskawa.pulses_per_deg: the arm's encoder pulses per degree (S, L, U, R, B, T), for pulse positions; absent =
  // unknown (the cell does not carry them): a pulse position is refused unless `waam import --pulses-per-deg` gives them
  std::optional<std::array<double, 6>> yaskawa_pulses_per_deg;
  // yaskawa.station_pulses_per_deg: the station's (positioner tilt, rotation), for EC positions; absent = unknown:
  // an EC position is refused, and so is a JBI export, unless --station-pulses-per-deg gives them
  std::optional<std::array<double, 2>> yaskawa_station_pulses_per_deg;
  // The scenario's top-level `target:` (absolute): the intended part as STL in the part frame P (plate top z = 0),
  // for the viewer's ghost and simulate's deviation measures; empty = none.
  std::filesystem::path target;
  std::string where;                          // "file:line: program" for messages
};

// The G-code reader's options of these settings: gcode.arc_on (else M<arc_on_m>), arc_off, feed_unit, dwell_p_unit.
GcodeReadOptions GcodeOptionsOf(const ProgramSettings& settings);

}  // namespace waam::planner
