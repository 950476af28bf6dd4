// Readers of robot programs and G-code into the reading model (program_motion.h), one per dialect, each in its own
// file; ReadProgramText picks one by the format (analysis::ReadProgramFile reads the file and detects it).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "planner/program/program_motion.h"

namespace waam::planner {

// The unit of a G-code F word (program.gcode.feed_unit).
enum class GcodeFeedUnit { kMmPerMin, kMmPerS };
constexpr std::array<EnumName<GcodeFeedUnit>, 2> EnumNames(GcodeFeedUnit) {
  return {{{GcodeFeedUnit::kMmPerMin, "mm_per_min"}, {GcodeFeedUnit::kMmPerS, "mm_per_s"}}};
}

// The unit of a G-code G4 P word (program.gcode.dwell_p_unit): milliseconds (Marlin, RepRapFirmware, Klipper, FANUC
// G04 P) or seconds (LinuxCNC, Grbl, Haas with a decimal point, ORNL Slicer 2's Arc Specialties syntax).
enum class GcodeDwellUnit { kMs, kS };
constexpr std::array<EnumName<GcodeDwellUnit>, 2> EnumNames(GcodeDwellUnit) {
  return {{{GcodeDwellUnit::kMs, "ms"}, {GcodeDwellUnit::kS, "s"}}};
}

// G-code settings: the codes that switch the arc (a G1 with a growing E extrudes, and welds, too), the units of F and
// of G4 P. A signal is a code word and optional parameter words that must be on the same line with these values:
// "M3", "M101", "G82", "M62 P1", "M42 P2 S1" (docs/PROGRAMS.md lists the dialects that use each).
struct GcodeReadOptions {
  std::vector<std::string> arc_on = {"M3"};   // M3: torch on (the spindle code most WAAM gantries reuse)
  std::vector<std::string> arc_off = {"M5"};  // M5: torch off
  GcodeFeedUnit feed_unit = GcodeFeedUnit::kMmPerMin;  // F in mm/min (G94, the standard) or mm/s (some WAAM controllers)
  GcodeDwellUnit dwell_p_unit = GcodeDwellUnit::kMs;   // G4 P in ms or s (G4 S, X and Sinumerik's G4 F are seconds)
};

// Checks one arc signal of program.gcode.arc_on / arc_off ("M3", "M62 P1"): a G or M code and parameter words, each
// a letter and a number. Throws InputError "<where> 'text': ..." naming the rule broken.
void CheckGcodeSignal(std::string_view text, const std::string& where);

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

// ABB RAPID module: MODULE ... ENDMODULE; data declarations (CONST, PERS, VAR; LOCAL, TASK; aggregates over several
// lines) of robtarget, jointtarget, speeddata, welddata, tooldata, wobjdata, num; PROC main run with the procedures
// it calls; MoveJ, MoveL, MoveC, MoveAbsJ, TriggJ/L/C, ArcLStart, ArcL, ArcLEnd, ArcCStart, ArcC, ArcCEnd (\On,
// \Off) to declared or literal targets, Offs() and RelTool() of literal or num offsets; speeddata (declared, a
// literal, v5 ... v7000, \V), welddata weld_speed, VelSet; the tool argument (tooldata declared, tool0) and \WObj
// (wobjdata declared); WaitTime; SetDO / Set / Reset of a weld or arc signal. IF, FOR, WHILE and TEST are warned.
ParsedProgram ReadAbbRapid(std::string_view text, const std::string& file);

// KUKA KRL: the .dat's DECL E6POS / POS / E6AXIS / AXIS, then the .src's DEF ... END: PTP, LIN, CIRC (names or
// aggregates), $VEL.CP and BAS(#CP_PARAMS, v) speeds (m/s), $BASE as a frame literal (else the scenario's user
// frame), $OUT[1] and ArcTech ARC_ON / ARC_OFF switching the arc, E1 / E2 the positioner (deg).
ParsedProgram ReadKukaKrl(std::string_view src, std::string_view dat, const std::string& src_file,
                          const std::string& dat_file, const ProgramFrames& frames = {});

// Yaskawa INFORM job (.JBI): /JOB, //NAME, //POS (///NPOS counts checked against the positions given; ///POSTYPE
// ROBOT or BASE: the robot frame, USER: user frame ///USER n from program.frames.uframe.n (in the robot frame, x y z
// mm, rx ry rz deg, R = Rz Ry Rx; else program.frame.user_frame_mm; else refused), PULSE: joint pulses through
// forward kinematics; ///TOOL n from program.frames.utool.n; C0000k=X,Y,Z mm,Rx,Ry,Rz deg; ///RCONF the IK branch;
// EC station pulses the positioner tilt and rotation), //INST (MOVJ, MOVL, MOVC circles of three points, MOVS as
// linear, V= mm/s or a variable, ARCON / ARCOF with their T= times, TIMER T=; CALL, JUMP, weaving, shifts and the
// like warned), END. A pulse position whose pulses per degree are not given is refused, naming the axis.
ParsedProgram ReadYaskawaJbi(std::string_view text, const std::string& file, const JbiReadOptions& options = {},
                             const ProgramFrames& frames = {});

// G-code (RS274/NGC and the Marlin / RepRap, FANUC, Sinumerik and WAAM controllers' dialects): words of a letter and
// a number, several per line in the controllers' order of execution (F, arc signals and other M codes, G4 dwell,
// modes, G92, motion); ';' and '( )' comments, N line numbers, '*' checksums, '/' block delete, '%'; modal G0, G1,
// G2 / G3 (I J K centres, relative or G90.1 absolute, or R) in the plane of G17 / G18 / G19; G20 / G21, G90 / G91,
// G92, M82 / M83, F modal in options.feed_unit, G4 P / S / X / F dwells; A (positioner tilt, deg), C (rotation,
// deg), the tool direction A3= B3= C3= (Sinumerik ORIVECT style). Positions are the TCP in the part frame. Unknown
// words and statements are warned, not refused.
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
