// The reading model of a robot program or G-code: a list of motions (joint / linear / circular) with a Cartesian
// pose or joint angles, positioner angles, speed and weld on/off, and the instructions the twin cannot execute.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "models/core/enum_names.h"
#include "planner/kinematics/opw_arm.h"

namespace waam::planner {

// The program dialects read and written (`--format`, scenario program.format).
enum class ProgramFormat { kCsv, kFanucLs, kAbbRapid, kKukaKrl, kYaskawaJbi, kGcode };
constexpr std::array<EnumName<ProgramFormat>, 6> EnumNames(ProgramFormat) {
  return {{{ProgramFormat::kCsv, "csv"},
           {ProgramFormat::kFanucLs, "fanuc_ls"},
           {ProgramFormat::kAbbRapid, "abb_rapid"},
           {ProgramFormat::kKukaKrl, "kuka_krl"},
           {ProgramFormat::kYaskawaJbi, "yaskawa_jbi"},
           {ProgramFormat::kGcode, "gcode"}}};
}
WAAM_ENUM_JSON(ProgramFormat)

enum class MotionKind { kJoint, kLinear, kCircular };
constexpr std::array<EnumName<MotionKind>, 3> EnumNames(MotionKind) {
  return {{{MotionKind::kJoint, "joint"}, {MotionKind::kLinear, "linear"}, {MotionKind::kCircular, "circular"}}};
}
WAAM_ENUM_JSON(MotionKind)

// Where a motion's Cartesian target is given: the user frame U (the scenario's program.frame, or the cell's default:
// the FANUC world frame, R lifted to the j2 height), the robot base frame R (a frame the program defines itself,
// e.g. an ABB wobjdata or a KRL BASE_DATA, already applied), the part frame P (G-code written with the tool tip in
// workpiece coordinates, as five-axis controllers with TCPM do), or the arm's world frame A (the cell's FANUC world
// frame whatever the scenario's program.frame: a FANUC UF 0 position, or a numbered user frame already applied).
enum class TargetFrame { kUser, kRobot, kPart, kArmWorld };

// One motion instruction as the controller would execute it.
struct ProgramMotion {
  MotionKind kind = MotionKind::kLinear;
  int line = 0;                     // 1-based line of the instruction in its file
  // Cartesian target: TCP pose in `frame`, mm; z of the rotation points from the TCP into the work (the torch
  // axis reversed). For kPart targets without an orientation, the rotation is the identity (a vertical torch).
  bool has_pose = false;
  TargetFrame frame = TargetFrame::kUser;
  Eigen::Isometry3d X_UT = Eigen::Isometry3d::Identity();
  bool has_joints = false;          // arm joints instead of a pose (run through forward kinematics)
  Joints6 q = Joints6::Zero();      // rad
  int config = -1;                  // IK branch (IkSolution::branch bits) when the program names it, else -1
  bool has_positioner = false;      // external axes / second group
  double tilt_rad = 0.0;
  double rotation_rad = 0.0;
  // The program numbers its external axes (E1, E2 / eax_a, eax_b / GP2 J1, J2) instead of naming them: tilt_rad
  // holds the first, rotation_rad the second (0 when it gives one). ProgramToPlan gives them to the cell's axes in
  // order: tilt and rotation, or a turntable's rotation alone.
  bool positioner_numbered = false;
  bool has_via = false;             // circular: the intermediate point, same frame as the target, mm
  Eigen::Vector3d via = Eigen::Vector3d::Zero();
  double speed_mm_s = 0.0;          // TCP speed of the move, mm/s; <= 0: unknown (the rapid speed is used)
  bool weld = false;                // arc on during this move
  double dwell_s = 0.0;             // the program waits this long at the target once there (G4, WAIT...), s >= 0
  // The program's tool: its TCP in the flange frame F, mm (a tool the program defines, or one it names that the
  // scenario's program.frames gives); false: the cell's torch.
  bool has_tool = false;
  Eigen::Isometry3d X_FT = Eigen::Isometry3d::Identity();
  std::string tool_name;            // how the program names its tool ("UT 2", "TOOL_DATA[4]", "tWeld"), for reports
};

// Frames and tools a program names by number without defining them, from the scenario's program.frames. Each is
// six numbers as the controller shows them: x, y, z (mm) and three angles (deg) in the dialect's own order (FANUC
// w, p, r with R = Rz(r) Ry(p) Rx(w); KUKA a, b, c with R = Rz(a) Ry(b) Rx(c)).
struct ProgramFrames {
  // FANUC UFRAME n (in the FANUC world frame), KUKA BASE_DATA[n] (in the robot's base frame), mm and deg.
  std::map<int, std::array<double, 6>> uframe;
  // FANUC UTOOL n, KUKA TOOL_DATA[n] (in the flange frame), mm and deg; an empty value: the cell's torch. An empty
  // table: every tool the program names without defining it is the cell's torch.
  std::map<int, std::optional<std::array<double, 6>>> utool;
  // The scenario gives program.frame.user_frame_mm: a FANUC program's one numbered user frame without a
  // program.frames entry is that frame.
  bool user_frame = false;
};

// An instruction the twin did not execute: what, how often, where first.
struct ProgramWarning {
  std::string what;
  int count = 0;
  int first_line = 0;
};

// A program as read: its motions in order and what was skipped.
struct ParsedProgram {
  std::string name;
  ProgramFormat format = ProgramFormat::kCsv;
  std::vector<ProgramMotion> motions;
  std::vector<ProgramWarning> warnings;
  // The motion count per kind name ("joint", "linear", "circular").
  std::map<std::string, std::size_t> MotionsByKind() const;
};

// Limits of what a reader accepts, as for STL files.
inline constexpr std::size_t kMaxProgramBytes = 512u << 20;     // 512 MiB of text
inline constexpr std::size_t kMaxProgramMotions = 20'000'000;   // motions (and positions) per program

namespace internal {

// Collects warnings by text, counting repeats and keeping the first line.
class WarningList {
 public:
  void Add(const std::string& what, int line);
  std::vector<ProgramWarning> Take() { return std::move(list_); }

 private:
  std::vector<ProgramWarning> list_;
  std::map<std::string, std::size_t> index_;
};

// The text's lines (without "\r\n" / "\n"), refusing more than kMaxProgramBytes.
std::vector<std::string_view> SplitProgramLines(std::string_view text, const std::string& file);

// A finite number, or InputError "file:line: <what> 'text' is not a number".
double ParseProgramNumber(std::string_view text, const std::string& file, int line, std::string_view what);

// A whole number within [lo, hi], or InputError "file:line: <what> 'text' must be a whole number in [lo, hi]".
int ParseProgramInteger(std::string_view text, const std::string& file, int line, std::string_view what, int lo,
                        int hi);

// `text` without leading and trailing blanks.
std::string_view TrimBlank(std::string_view text);

// Upper-case copy.
std::string Upper(std::string_view text);

// Throws InputError when `motions` already holds kMaxProgramMotions.
void CheckMotionCount(std::size_t motions, const std::string& file, int line);

// Rotation Rz(a) Ry(b) Rx(c) (angles in rad): FANUC W P R = (c, b, a), KUKA A B C = (a, b, c).
Eigen::Matrix3d RotationZyx(double a, double b, double c);

// The pose of six numbers x, y, z (mm), a, b, c (deg) with R = Rz(a) Ry(b) Rx(c) (KUKA's order; FANUC's w, p, r is
// (r, p, w) here).
Eigen::Isometry3d PoseXyzAbc(double x, double y, double z, double a_deg, double b_deg, double c_deg);

// Sets `m`'s dwell to `seconds` more, or warns "wait before the first motion" when there is none yet.
void AddDwell(std::vector<ProgramMotion>* motions, double seconds, int line, WarningList* warnings);

}  // namespace internal
}  // namespace waam::planner
