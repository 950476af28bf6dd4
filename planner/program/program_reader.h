// Readers of robot programs and G-code into the reading model (program_motion.h), one per dialect, each in its own
// file; ReadProgramText picks one by the format (analysis::ReadProgramFile reads the file and detects it).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <string_view>

#include "planner/program/program_motion.h"

namespace waam::planner {

// The unit of a G-code F word (program.gcode.feed_unit).
enum class GcodeFeedUnit { kMmPerMin, kMmPerS };
constexpr std::array<EnumName<GcodeFeedUnit>, 2> EnumNames(GcodeFeedUnit) {
  return {{{GcodeFeedUnit::kMmPerMin, "mm_per_min"}, {GcodeFeedUnit::kMmPerS, "mm_per_s"}}};
}

// G-code settings: which M-codes switch the arc (a G1 with a growing E extrudes, and welds, too), the feed's unit.
struct GcodeReadOptions {
  int arc_on_m = 3;    // M3: torch on (the spindle code most WAAM gantries reuse)
  int arc_off_m = 5;   // M5: torch off
  GcodeFeedUnit feed_unit = GcodeFeedUnit::kMmPerMin;  // F in mm/min (G94, the standard) or mm/s (some WAAM controllers)
};

// Yaskawa INFORM settings: the controller's encoder pulses per degree (0 = unknown: a pulse position is refused).
struct JbiReadOptions {
  std::array<double, 6> robot_pulses_per_deg = {};    // axes S, L, U, R, B, T
  std::array<double, 2> station_pulses_per_deg = {};  // station axes 1 and 2: positioner tilt, rotation
};

// Each reader takes the whole text and the file name for messages, and throws InputError "file:line: what" for a
// syntax error, a position used and not defined, a number that is not finite, or a file past kMaxProgramBytes /
// kMaxProgramMotions. Instructions the twin does not execute are counted in ParsedProgram::warnings.

// FANUC LS: /PROG, /ATTR, /APPL, /MN (J, L, C motions; Arc Start/End as instructions and motion options; registers,
// CALL, IF, JMP, LBL, comments, Weave, Offset, TOOL_OFFSET warned), /POS (GP1 Cartesian with CONFIG or joints, GP2
// positioner joints), /END.
ParsedProgram ReadFanucLs(std::string_view text, const std::string& file, const ProgramFrames& frames = {});

// ABB RAPID module: robtarget / jointtarget / speeddata / welddata / wobjdata declarations (CONST, PERS, VAR);
// MoveJ, MoveL, MoveC, MoveAbsJ, ArcLStart, ArcL, ArcLEnd, ArcCStart, ArcC, ArcCEnd, SetDO of a weld/arc signal.
ParsedProgram ReadAbbRapid(std::string_view text, const std::string& file);

// KUKA KRL: the .dat's DECL E6POS / POS / E6AXIS / AXIS, then the .src's DEF ... END: PTP, LIN, CIRC (names or
// aggregates), $VEL.CP and BAS(#CP_PARAMS, v) speeds (m/s), $BASE as a frame literal (else the scenario's user
// frame), $OUT[1] and ArcTech ARC_ON / ARC_OFF switching the arc, E1 / E2 the positioner (deg).
ParsedProgram ReadKukaKrl(std::string_view src, std::string_view dat, const std::string& src_file,
                          const std::string& dat_file, const ProgramFrames& frames = {});

// Yaskawa INFORM job (.JBI): /JOB, //NAME, //POS (///NPOS counts checked against the positions given; ///POSTYPE
// ROBOT or BASE: the arm's base frame, USER: the scenario's user frame, PULSE: joint pulses through forward
// kinematics; C0000k=X,Y,Z mm,Rx,Ry,Rz deg with R = Rz Ry Rx; ///RCONF the IK branch; EC station pulses the
// positioner tilt and rotation), //INST (MOVJ, MOVL, MOVC circles of three points, MOVS as linear, V= mm/s or a
// variable, ARCON / ARCOF; CALL, JUMP, TIMER, weaving, shifts and the like warned), END. A pulse position whose
// pulses per degree are not given is refused, naming the axis.
ParsedProgram ReadYaskawaJbi(std::string_view text, const std::string& file, const JbiReadOptions& options = {});

// G-code: G0, G1, G2, G3 (XY plane), G20/G21, G90/G91, F, E, A (positioner tilt, deg), C (rotation, deg), the tool
// direction A3= B3= C3= (Sinumerik ORIVECT style), arc on/off M-codes. Positions are the TCP in the part frame.
ParsedProgram ReadGcode(std::string_view text, const std::string& file, const GcodeReadOptions& options = {});

// The CSV program table that `waam check` writes (program.csv): TCP in the user frame, A B C, positioner angles.
ParsedProgram ReadProgramCsv(std::string_view text, const std::string& file);

// The format of `path` from its extension (.ls, .mod/.prg, .src/.dat, .jbi, .nc/.gcode/.ngc/.tap, .csv) or, failing that, its first
// lines. Throws InputError when neither tells.
ProgramFormat DetectProgramFormat(const std::filesystem::path& path, std::string_view text);


// Reads `text` with the reader of `format`; `file` names it in messages. KRL: the .src text followed by its .dat.
ParsedProgram ReadProgramText(std::string_view text, const std::string& file, ProgramFormat format,
                              const GcodeReadOptions& gcode = {}, const JbiReadOptions& jbi = {},
                              const ProgramFrames& frames = {});

// The format an extension names (.ls, .mod/.prg/.modx, .src/.dat, .jbi, .nc/.gcode/.ngc/.tap/.g/.mpf, .csv; any
// case), or empty.
std::optional<ProgramFormat> ProgramFormatOfExtension(const std::filesystem::path& path);

}  // namespace waam::planner
