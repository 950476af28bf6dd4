// Readers of robot programs and G-code into the reading model (program_motion.h), one per dialect, each in its own
// file; ReadProgramFile picks one by the format or the file's extension and content.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "planner/program/program_motion.h"

namespace waam::planner {

// G-code settings: which M-codes switch the arc (a G1 with a growing E extrudes, and welds, too).
struct GcodeReadOptions {
  int arc_on_m = 3;    // M3: torch on (the spindle code most WAAM gantries reuse)
  int arc_off_m = 5;   // M5: torch off
};

// Each reader takes the whole text and the file name for messages, and throws InputError "file:line: what" for a
// syntax error, a position used and not defined, a number that is not finite, or a file past kMaxProgramBytes /
// kMaxProgramMotions. Instructions the twin does not execute are counted in ParsedProgram::warnings.

// FANUC LS: /PROG, /ATTR, /APPL, /MN (J, L, C motions; Arc Start/End as instructions and motion options; registers,
// CALL, IF, JMP, LBL, comments, Weave, Offset, TOOL_OFFSET warned), /POS (GP1 Cartesian with CONFIG or joints, GP2
// positioner joints), /END.
ParsedProgram ReadFanucLs(std::string_view text, const std::string& file);

// ABB RAPID module: robtarget / jointtarget / speeddata / welddata / wobjdata declarations (CONST, PERS, VAR);
// MoveJ, MoveL, MoveC, MoveAbsJ, ArcLStart, ArcL, ArcLEnd, ArcCStart, ArcC, ArcCEnd, SetDO of a weld/arc signal.
ParsedProgram ReadAbbRapid(std::string_view text, const std::string& file);

// KUKA KRL: the .dat's DECL E6POS / POS / E6AXIS / AXIS, then the .src's DEF ... END: PTP, LIN, CIRC (names or
// aggregates), $VEL.CP and BAS(#CP_PARAMS, v) speeds (m/s), $BASE as a frame literal (else the scenario's user
// frame), $OUT[1] and ArcTech ARC_ON / ARC_OFF switching the arc, E1 / E2 the positioner (deg).
ParsedProgram ReadKukaKrl(std::string_view src, std::string_view dat, const std::string& src_file,
                          const std::string& dat_file);

// G-code: G0, G1, G2, G3 (XY plane), G20/G21, G90/G91, F, E, A (positioner tilt, deg), C (rotation, deg), the tool
// direction A3= B3= C3= (Sinumerik ORIVECT style), arc on/off M-codes. Positions are the TCP in the part frame.
ParsedProgram ReadGcode(std::string_view text, const std::string& file, const GcodeReadOptions& options = {});

// The CSV program table that `waam check` writes (program.csv): TCP in the user frame, A B C, positioner angles.
ParsedProgram ReadProgramCsv(std::string_view text, const std::string& file);

// The format of `path` from its extension (.ls, .mod/.prg, .src/.dat, .nc/.gcode/.ngc/.tap, .csv) or, failing that, its first
// lines. Throws InputError when neither tells.
ProgramFormat DetectProgramFormat(const std::filesystem::path& path, std::string_view text);

// Reads `path` (at most kMaxProgramBytes) with the reader of `format` (empty: detected).
ParsedProgram ReadProgramFile(const std::filesystem::path& path, std::optional<ProgramFormat> format,
                              const GcodeReadOptions& gcode = {});

// Reads `text` with the reader of `format`; `file` names it in messages. KRL: the .src text followed by its .dat.
ParsedProgram ReadProgramText(std::string_view text, const std::string& file, ProgramFormat format,
                              const GcodeReadOptions& gcode = {});

}  // namespace waam::planner
