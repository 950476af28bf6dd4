// Yaskawa INFORM job (.JBI) reader: //POS (///NPOS counts, ///POSTYPE ROBOT | BASE | USER | PULSE, ///RCONF, C, BC,
// EC, P, BP, EX positions) then //INST (MOVJ, MOVL, MOVC, MOVS, ARCON / ARCOF; other instructions warned).
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/program/program_reader.h"

namespace waam::planner {
namespace {

using internal::ParseProgramNumber;
using internal::TrimBlank;
using internal::Upper;

enum class JbiPosType { kRobot, kBase, kUser, kPulse };

struct JbiPosition {
  std::vector<double> values;
  JbiPosType type = JbiPosType::kRobot;
  int config = -1;  // IK branch bits from ///RCONF
  int line = 0;
};

// The six position kinds of ///NPOS, in its order.
constexpr std::array<const char*, 6> kKinds = {"C", "BC", "EC", "P", "BP", "EX"};

// "EC00012" -> kind 2, index 12; false when the text is not a position name.
bool SplitPositionName(std::string_view name, int* kind, long* index) {
  std::size_t letters = 0;
  while (letters < name.size() && std::isalpha(static_cast<unsigned char>(name[letters]))) ++letters;
  if (letters == 0 || letters == name.size() || name.size() - letters > 5) return false;
  const std::string k = Upper(name.substr(0, letters));
  *kind = -1;
  for (int i = 0; i < 6; ++i) {
    if (k == kKinds[i]) *kind = i;
  }
  if (*kind < 0) return false;
  long v = 0;
  for (std::size_t i = letters; i < name.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return false;
    v = v * 10 + (name[i] - '0');
  }
  *index = v;
  return true;
}

// ///RCONF flip,arm,front/back,... -> IK branch bits (0 shoulder back, 1 elbow down, 2 wrist flipped).
int ParseRconf(std::string_view text, const std::string& file, int line) {
  std::vector<int> digits;
  while (!text.empty() && digits.size() < 32) {
    const std::size_t comma = text.find(',');
    digits.push_back(internal::ParseProgramInteger(text.substr(0, comma), file, line, "///RCONF digit", 0, 1));
    text = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
  }
  WAAM_THROW_UNLESS(digits.size() >= 3, file << ":" << line << ": ///RCONF needs at least flip, arm, front/back");
  return (digits[2] ? 1 : 0) | (digits[1] ? 2 : 0) | (digits[0] ? 0 : 4);
}

// The job's motion state while //INST is read.
struct JbiState {
  bool arc_on = false;
  double v_mm_s = 0.0;  // the last V= (INFORM keeps the speed of the previous move of the same kind)
};

}  // namespace

ParsedProgram ReadYaskawaJbi(std::string_view text, const std::string& file, const JbiReadOptions& options) {
  ParsedProgram program;
  program.format = ProgramFormat::kYaskawaJbi;
  internal::WarningList warnings;
  const std::vector<std::string_view> lines = internal::SplitProgramLines(text, file);

  enum class Section { kNone, kJob, kPos, kInst } section = Section::kNone;
  std::array<long, 6> npos = {-1, -1, -1, -1, -1, -1};
  int npos_line = 0;
  std::array<std::map<long, JbiPosition>, 6> positions;
  std::size_t position_count = 0;
  JbiPosType postype = JbiPosType::kRobot;
  bool postype_given = false;
  int config = -1;
  int user_frame = -1;
  bool ended = false;
  JbiState state;
  const JbiPosition* pending_station = nullptr;  // a station-only move's position, for the next robot move
  // MOVC points waiting for the rest of their circle: the first is reached by a linear move, then (via, end) pairs.
  std::vector<ProgramMotion> circle;
  auto flush_circle = [&]() {
    for (std::size_t k = 0; k < circle.size();) {
      // The circle's first point is where the robot already stands when it was taught there (the usual case):
      // no move of its own.
      if (k == 0 && circle.size() >= 3 && !program.motions.empty()) {
        const ProgramMotion& last = program.motions.back();
        if (last.has_pose && circle[0].has_pose && last.frame == circle[0].frame &&
            last.X_UT.isApprox(circle[0].X_UT, 1e-12)) {
          ++k;
          continue;
        }
      }
      if (k == 0 || k + 1 == circle.size()) {
        if (k > 0) warnings.Add("MOVC without the third point of its circle followed as a linear move", circle[k].line);
        circle[k].kind = MotionKind::kLinear;
        program.motions.push_back(circle[k]);
        ++k;
      } else {
        ProgramMotion end = circle[k + 1];
        end.kind = MotionKind::kCircular;
        end.has_via = true;
        end.via = circle[k].X_UT.translation();
        WAAM_THROW_UNLESS(circle[k].has_pose && end.has_pose && circle[k].frame == end.frame,
                          file << ":" << circle[k].line << ": MOVC through a pulse position and a Cartesian one, "
                               << "or positions in different frames");
        program.motions.push_back(end);
        k += 2;
      }
    }
    circle.clear();
  };

  for (std::size_t li = 0; li < lines.size() && !ended; ++li) {
    const int line = static_cast<int>(li) + 1;
    const std::string_view l = TrimBlank(lines[li]);
    if (l.empty()) continue;
    const std::string u = Upper(l);
    if (section == Section::kNone) {
      WAAM_THROW_UNLESS(u == "/JOB", file << ":" << line << ": a JBI job starts with /JOB, not '"
                                          << std::string(l.substr(0, 30)) << "'");
      section = Section::kJob;
      continue;
    }
    if (u.compare(0, 6, "//NAME") == 0) {
      program.name = std::string(TrimBlank(l.substr(6)));
      continue;
    }
    if (u == "//POS") {
      WAAM_THROW_UNLESS(section == Section::kJob, file << ":" << line << ": //POS after //INST");
      section = Section::kPos;
      continue;
    }
    if (u == "//INST") {
      WAAM_THROW_UNLESS(section != Section::kInst, file << ":" << line << ": a second //INST");
      if (section == Section::kPos) {
        // Every kind of position as many times as ///NPOS says.
        WAAM_THROW_UNLESS(npos_line > 0, file << ":" << line << ": //POS without ///NPOS");
        for (int k = 0; k < 6; ++k) {
          WAAM_THROW_UNLESS(static_cast<long>(positions[k].size()) == npos[k],
                            file << ":" << npos_line << ": ///NPOS says " << npos[k] << " " << kKinds[k]
                                 << " positions, " << positions[k].size() << " are given");
        }
      }
      section = Section::kInst;
      continue;
    }
    if (section == Section::kJob) {
      WAAM_THROW_UNLESS(u.compare(0, 3, "///") == 0 || u.compare(0, 2, "//") == 0,
                        file << ":" << line << ": expected //POS or //INST, not '" << std::string(l.substr(0, 30))
                             << "'");
      continue;
    }

    if (section == Section::kPos) {
      if (u.compare(0, 3, "///") == 0) {
        const std::string key = u.substr(3, u.find_first_of(" \t") == std::string::npos ? std::string::npos
                                                                                        : u.find_first_of(" \t") - 3);
        const std::string_view value = TrimBlank(l.substr(3 + key.size()));
        if (key == "NPOS") {
          WAAM_THROW_UNLESS(npos_line == 0, file << ":" << line << ": a second ///NPOS");
          npos_line = line;
          std::string_view rest = value;
          for (int k = 0; k < 6; ++k) {
            const std::size_t comma = rest.find(',');
            WAAM_THROW_UNLESS(!rest.empty() && (k == 5 || comma != std::string_view::npos),
                              file << ":" << line << ": ///NPOS needs six counts (C, BC, EC, P, BP, EX)");
            npos[k] = internal::ParseProgramInteger(rest.substr(0, comma), file, line, "///NPOS count", 0,
                                                    static_cast<int>(kMaxProgramMotions));
            rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
          }
          WAAM_THROW_UNLESS(TrimBlank(rest).empty(), file << ":" << line << ": ///NPOS has more than six counts");
        } else if (key == "POSTYPE") {
          const std::string t = Upper(value);
          if (t == "ROBOT") {
            postype = JbiPosType::kRobot;
          } else if (t == "BASE") {
            postype = JbiPosType::kBase;
          } else if (t == "USER") {
            postype = JbiPosType::kUser;
          } else if (t == "PULSE") {
            postype = JbiPosType::kPulse;
          } else {
            WAAM_THROW(file << ":" << line << ": ///POSTYPE '" << std::string(value.substr(0, 20))
                            << "': must be ROBOT, BASE, USER or PULSE");
          }
          postype_given = true;
        } else if (key == "RCONF") {
          config = ParseRconf(value, file, line);
        } else if (key == "USER") {
          const int n = internal::ParseProgramInteger(value, file, line, "///USER", 0, 999);
          if (user_frame >= 0 && n != user_frame) {
            warnings.Add("a second user frame taken as the scenario's program.frame too", line);
          }
          user_frame = n;
        }
        // ///TOOL: the cell's torch; ///RECTAN, ///PULSE: the form that ///POSTYPE already says.
        continue;
      }
      // A position: NAME=v1,v2,...
      const std::size_t eq = l.find('=');
      int kind = -1;
      long index = 0;
      WAAM_THROW_UNLESS(eq != std::string_view::npos && SplitPositionName(TrimBlank(l.substr(0, eq)), &kind, &index),
                        file << ":" << line << ": expected a position such as C00000=x,y,z,rx,ry,rz, not '"
                             << std::string(l.substr(0, 30)) << "'");
      WAAM_THROW_UNLESS(npos_line > 0, file << ":" << line << ": a position before ///NPOS");
      const std::string name(TrimBlank(l.substr(0, eq)));
      WAAM_THROW_UNLESS(index < npos[kind], file << ":" << line << ": " << name << " is past the " << npos[kind]
                                                 << " " << kKinds[kind] << " positions ///NPOS declares");
      WAAM_THROW_UNLESS(postype_given, file << ":" << line << ": " << name << " before any ///POSTYPE");
      internal::CheckMotionCount(position_count++, file, line);
      JbiPosition pos;
      pos.type = postype;
      pos.config = config;
      pos.line = line;
      std::string_view rest = l.substr(eq + 1);
      while (true) {
        const std::size_t comma = rest.find(',');
        pos.values.push_back(ParseProgramNumber(rest.substr(0, comma), file, line, name + " value"));
        WAAM_THROW_UNLESS(pos.values.size() <= 12, file << ":" << line << ": " << name << " has more than 12 values");
        if (comma == std::string_view::npos) break;
        rest = rest.substr(comma + 1);
      }
      const bool robot = kind == 0 || kind == 3;
      const bool station = kind == 2 || kind == 5;
      if (robot) {
        WAAM_THROW_UNLESS(pos.values.size() == 6, file << ":" << line << ": " << name << " has "
                                                       << pos.values.size() << " values; a robot position has six");
      }
      if (station) {
        WAAM_THROW_UNLESS(postype == JbiPosType::kPulse,
                          file << ":" << line << ": " << name << ": station positions are pulses (///POSTYPE PULSE)");
      }
      WAAM_THROW_UNLESS(positions[kind].emplace(index, std::move(pos)).second,
                        file << ":" << line << ": " << name << " is defined twice");
      continue;
    }

    // //INST
    if (u.compare(0, 2, "//") == 0) continue;  // ///DATE, ///COMM, ///ATTR, ///GROUP1, ///FRAME, ///LVARS
    if (l.front() == '\'' || l.front() == '*') continue;  // comment, label
    std::string word = u.substr(0, u.find_first_of(" \t"));
    const bool second_group = !word.empty() && word.front() == '+';
    if (second_group) word = word.substr(1);
    const bool movj = word == "MOVJ", movl = word == "MOVL", movc = word == "MOVC", movs = word == "MOVS";
    if (!movc) flush_circle();
    if (word == "NOP") continue;
    if (word == "END") {
      ended = true;
      continue;
    }
    if (word == "ARCON" || word == "ARCOF") {
      state.arc_on = word == "ARCON";
      continue;
    }
    if (word == "TIMER") {
      // TIMER T=t (s): the torch waits at its last target; a time from a variable is warned.
      const std::size_t t = u.find("T=");
      WAAM_THROW_UNLESS(t != std::string::npos, file << ":" << line << ": TIMER without its T=");
      const std::string value(TrimBlank(std::string_view(u).substr(t + 2)));
      if (value.empty() || !(std::isdigit(static_cast<unsigned char>(value[0])) || value[0] == '.')) {
        warnings.Add("TIMER of a variable not in the timeline", line);
      } else {
        internal::AddDwell(&program.motions, ParseProgramNumber(value, file, line, "TIMER T"), line, &warnings);
      }
      continue;
    }
    if (!movj && !movl && !movc && !movs) {
      warnings.Add("instruction " + word.substr(0, 24) + " not executed", line);
      continue;
    }
    if (movs) warnings.Add("MOVS (spline) followed as linear moves through its points", line);
    internal::CheckMotionCount(program.motions.size() + circle.size(), file, line);
    ProgramMotion m;
    m.line = line;
    m.kind = movj ? MotionKind::kJoint : MotionKind::kLinear;
    const JbiPosition* robot = nullptr;
    const JbiPosition* station = nullptr;
    bool speed_given = false;
    std::string_view rest = TrimBlank(l.substr(word.size() + (second_group ? 1 : 0)));
    while (!rest.empty()) {
      const std::size_t end = rest.find_first_of(" \t");
      const std::string_view token = rest.substr(0, end);
      rest = end == std::string_view::npos ? std::string_view() : TrimBlank(rest.substr(end));
      const std::string t = Upper(token);
      int kind = -1;
      long index = 0;
      if (SplitPositionName(token, &kind, &index)) {
        const auto found = positions[kind].find(index);
        WAAM_THROW_UNLESS(found != positions[kind].end(),
                          file << ":" << line << ": " << std::string(token) << " is used but not defined in //POS");
        if (kind == 0 || kind == 3) {
          robot = &found->second;
        } else if (kind == 2 || kind == 5) {
          station = &found->second;
        } else {
          warnings.Add("base axis positions (" + std::string(kKinds[kind]) + ") not executed: the cell has no "
                       "travelling base", line);
        }
        continue;
      }
      const std::size_t eq = t.find('=');
      const std::string key = t.substr(0, eq);
      if (key == "V" && eq != std::string::npos) {
        const std::string_view v = token.substr(eq + 1);
        if (!v.empty() && std::isalpha(static_cast<unsigned char>(v.front()))) {
          warnings.Add("speed from a variable (V=" + Upper(v.substr(0, 8)) + "): the scenario's speed used", line);
          state.v_mm_s = 0.0;
        } else {
          state.v_mm_s = ParseProgramNumber(v, file, line, "V=");
          WAAM_THROW_UNLESS(state.v_mm_s > 0.0, file << ":" << line << ": V= must be > 0 mm/s");
        }
        speed_given = true;
      } else if (key == "VJ" || key == "PL" || key == "CR" || key == "ACC" || key == "DEC" || key == "NWAIT" ||
                 key == "VR" || key == "VE" || key == "FPT") {
        // Joint speed (percent), blending, acceleration, orientation speeds: no effect on the path's points.
      } else {
        warnings.Add(word + " option " + key.substr(0, 16) + " not executed", line);
      }
    }
    WAAM_THROW_UNLESS(robot != nullptr || station != nullptr,
                      file << ":" << line << ": " << word << " needs a position (C00000)");
    if (robot == nullptr) {
      warnings.Add("station-only move not executed alone: its angles are taken by the next robot move", line);
      pending_station = station;
      continue;
    }
    if (station == nullptr) station = pending_station;
    pending_station = nullptr;
    if (station != nullptr) {
      WAAM_THROW_UNLESS(station->values.size() >= 2,
                        file << ":" << station->line << ": a station position needs two axes (tilt, rotation), "
                             << station->values.size() << " given");
      const double tp = options.station_pulses_per_deg[0], rp = options.station_pulses_per_deg[1];
      WAAM_THROW_UNLESS(tp > 0.0 && rp > 0.0,
                        file << ":" << station->line << ": station positions are encoder pulses and the station's "
                             << "pulses per degree are unknown: give program.yaskawa.station_pulses_per_deg "
                             << "[tilt, rotation] or --station-pulses-per-deg");
      m.has_positioner = true;
      m.tilt_rad = station->values[0] / tp / kDeg;
      m.rotation_rad = station->values[1] / rp / kDeg;
      if (station->values.size() > 2) warnings.Add("station axes past the second not executed", station->line);
    }
    const JbiPosition& p = *robot;
    if (p.type == JbiPosType::kPulse) {
      static const char* const kAxes[6] = {"S", "L", "U", "R", "B", "T"};
      for (int j = 0; j < 6; ++j) {
        const double ppd = options.robot_pulses_per_deg[j];
        WAAM_THROW_UNLESS(ppd > 0.0, file << ":" << p.line << ": a pulse position and the robot's pulses per degree "
                                          << "are unknown (axis " << kAxes[j]
                                          << "): give program.yaskawa.pulses_per_deg [S, L, U, R, B, T] or --pulses-per-deg");
        m.q[j] = p.values[j] / ppd / kDeg;
      }
      m.has_joints = true;
    } else {
      m.has_pose = true;
      m.frame = p.type == JbiPosType::kUser ? TargetFrame::kUser : TargetFrame::kRobot;
      // Rx, Ry, Rz: fixed angles about x, then y, then z: R = Rz Ry Rx.
      m.X_UT.translation() = Eigen::Vector3d(p.values[0], p.values[1], p.values[2]);
      m.X_UT.linear() = internal::RotationZyx(p.values[5] / kDeg, p.values[4] / kDeg, p.values[3] / kDeg);
      m.config = p.config;
    }
    if (!movj && !speed_given && state.v_mm_s <= 0.0) {
      warnings.Add(word + " before any V=: the scenario's speed used", line);
    }
    m.speed_mm_s = movj ? 0.0 : state.v_mm_s;
    m.weld = state.arc_on && !movj;
    if (movc) {
      circle.push_back(m);
    } else {
      program.motions.push_back(m);
    }
  }
  flush_circle();
  WAAM_THROW_UNLESS(section != Section::kNone, file << ": not a JBI job (no /JOB line)");
  WAAM_THROW_UNLESS(section != Section::kPos,
                    file << ":" << lines.size() << ": the job ends inside //POS (no //INST): it is truncated");
  WAAM_THROW_UNLESS(ended, file << ":" << lines.size() << ": no END: the job is truncated");
  program.warnings = warnings.Take();
  return program;
}

}  // namespace waam::planner
