// Yaskawa INFORM job (.JBI) reader: the sections /JOB, //NAME, //POS (position header lines and C, BC, EC, P, BP,
// EX variables) and //INST, each instruction tokenized and run by a small function of its kind.
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/program/program_reader.h"
#include "planner/program/program_tokens.h"

namespace waam::planner {
namespace {

using internal::TokenCursor;
using internal::TokenKind;
using internal::TrimBlank;
using internal::Upper;

enum class JbiPosType { kRobot, kBase, kUser, kPulse };

struct JbiPosition {
  std::vector<double> values;
  JbiPosType type = JbiPosType::kRobot;
  int config = -1;  // IK branch bits from ///RCONF
  int user = -1;    // ///USER frame number in force
  int tool = -1;    // ///TOOL number in force
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

struct JbiInstLine {
  std::string text;
  int line = 0;
};

// The job as its sections hold it.
struct JbiJob {
  std::string name;
  std::array<long, 6> npos = {-1, -1, -1, -1, -1, -1};
  int npos_line = 0;
  std::array<std::map<long, JbiPosition>, 6> positions;
  std::vector<JbiInstLine> inst;
  // The header lines in force while //POS is read.
  JbiPosType postype = JbiPosType::kRobot;
  bool postype_given = false;
  int config = -1, user = -1, tool = -1;
  std::size_t position_count = 0;
};

// ///NPOS c,bc,ec,p,bp,ex.
void ReadJbiNpos(JbiJob* job, std::string_view value, const std::string& file, int line) {
  WAAM_THROW_UNLESS(job->npos_line == 0, file << ":" << line << ": a second ///NPOS");
  job->npos_line = line;
  for (int k = 0; k < 6; ++k) {
    const std::size_t comma = value.find(',');
    WAAM_THROW_UNLESS(!value.empty() && (k == 5 || comma != std::string_view::npos),
                      file << ":" << line << ": ///NPOS needs six counts (C, BC, EC, P, BP, EX)");
    job->npos[k] = internal::ParseProgramInteger(value.substr(0, comma), file, line, "///NPOS count", 0,
                                                 static_cast<int>(kMaxProgramMotions));
    value = comma == std::string_view::npos ? std::string_view() : value.substr(comma + 1);
  }
  WAAM_THROW_UNLESS(TrimBlank(value).empty(), file << ":" << line << ": ///NPOS has more than six counts");
}

// A //POS header line: ///NPOS, ///POSTYPE, ///RCONF, ///USER, ///TOOL (///RECTAN and ///PULSE repeat what ///POSTYPE
// says).
void ReadJbiPosHeader(JbiJob* job, std::string_view l, const std::string& file, int line) {
  const std::string u = Upper(l);
  const std::size_t blank = u.find_first_of(" \t");
  const std::string key = u.substr(3, blank == std::string::npos ? std::string::npos : blank - 3);
  const std::string_view value = TrimBlank(l.substr(3 + key.size()));
  if (key == "NPOS") {
    ReadJbiNpos(job, value, file, line);
  } else if (key == "POSTYPE") {
    static const std::map<std::string, JbiPosType> kTypes = {{"ROBOT", JbiPosType::kRobot},
                                                             {"BASE", JbiPosType::kBase},
                                                             {"USER", JbiPosType::kUser},
                                                             {"PULSE", JbiPosType::kPulse}};
    const auto t = kTypes.find(Upper(value));
    WAAM_THROW_UNLESS(t != kTypes.end(), file << ":" << line << ": ///POSTYPE '" << std::string(value.substr(0, 20))
                                              << "': must be ROBOT, BASE, USER or PULSE");
    job->postype = t->second;
    job->postype_given = true;
  } else if (key == "RCONF") {
    job->config = ParseRconf(value, file, line);
  } else if (key == "USER" || key == "TOOL") {
    (key == "USER" ? job->user : job->tool) = internal::ParseProgramInteger(value, file, line, "///" + key, 0, 999);
  }
}

// "C00002=x,y,z,rx,ry,rz": a position variable, with the header lines in force.
void ReadJbiPosition(JbiJob* job, std::string_view l, const std::string& file, int line) {
  const std::size_t eq = l.find('=');
  int kind = -1;
  long index = 0;
  WAAM_THROW_UNLESS(eq != std::string_view::npos && SplitPositionName(TrimBlank(l.substr(0, eq)), &kind, &index),
                    file << ":" << line << ": expected a position such as C00000=x,y,z,rx,ry,rz, not '"
                         << std::string(l.substr(0, 30)) << "'");
  WAAM_THROW_UNLESS(job->npos_line > 0, file << ":" << line << ": a position before ///NPOS");
  const std::string name(TrimBlank(l.substr(0, eq)));
  WAAM_THROW_UNLESS(index < job->npos[kind], file << ":" << line << ": " << name << " is past the " << job->npos[kind]
                                                  << " " << kKinds[kind] << " positions ///NPOS declares");
  WAAM_THROW_UNLESS(job->postype_given, file << ":" << line << ": " << name << " before any ///POSTYPE");
  internal::CheckMotionCount(job->position_count++, file, line);
  JbiPosition pos{{}, job->postype, job->config, job->user, job->tool, line};
  std::string_view rest = l.substr(eq + 1);
  while (true) {
    const std::size_t comma = rest.find(',');
    pos.values.push_back(internal::ParseProgramNumber(rest.substr(0, comma), file, line, name + " value"));
    WAAM_THROW_UNLESS(pos.values.size() <= 12, file << ":" << line << ": " << name << " has more than 12 values");
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  if (kind == 0 || kind == 3) {
    WAAM_THROW_UNLESS(pos.values.size() == 6, file << ":" << line << ": " << name << " has " << pos.values.size()
                                                   << " values; a robot position has six");
  }
  WAAM_THROW_UNLESS(!(kind == 2 || kind == 5) || job->postype == JbiPosType::kPulse,
                    file << ":" << line << ": " << name << ": station positions are pulses (///POSTYPE PULSE)");
  WAAM_THROW_UNLESS(job->positions[kind].emplace(index, std::move(pos)).second,
                    file << ":" << line << ": " << name << " is defined twice");
}

// The sections: /JOB first, //NAME, //POS (every kind as many times as ///NPOS says), //INST, END.
JbiJob ReadJbiSections(const std::vector<std::string_view>& lines, const std::string& file) {
  JbiJob job;
  enum class Section { kNone, kJob, kPos, kInst } section = Section::kNone;
  for (std::size_t li = 0; li < lines.size(); ++li) {
    const int line = static_cast<int>(li) + 1;
    const std::string_view l = TrimBlank(lines[li]);
    if (l.empty()) continue;
    const std::string u = Upper(l.substr(0, 8));
    if (section == Section::kNone) {
      WAAM_THROW_UNLESS(Upper(l) == "/JOB", file << ":" << line << ": a JBI job starts with /JOB, not '"
                                                 << std::string(l.substr(0, 30)) << "'");
      section = Section::kJob;
    } else if (u.compare(0, 6, "//NAME") == 0) {
      job.name = std::string(TrimBlank(l.substr(6)));
    } else if (Upper(l) == "//POS") {
      WAAM_THROW_UNLESS(section == Section::kJob, file << ":" << line << ": //POS after //INST");
      section = Section::kPos;
    } else if (Upper(l) == "//INST") {
      WAAM_THROW_UNLESS(section != Section::kInst, file << ":" << line << ": a second //INST");
      if (section == Section::kPos) {
        WAAM_THROW_UNLESS(job.npos_line > 0, file << ":" << line << ": //POS without ///NPOS");
        for (int k = 0; k < 6; ++k) {
          WAAM_THROW_UNLESS(static_cast<long>(job.positions[k].size()) == job.npos[k],
                            file << ":" << job.npos_line << ": ///NPOS says " << job.npos[k] << " " << kKinds[k]
                                 << " positions, " << job.positions[k].size() << " are given");
        }
      }
      section = Section::kInst;
    } else if (section == Section::kJob) {
      WAAM_THROW_UNLESS(u.compare(0, 2, "//") == 0, file << ":" << line << ": expected //POS or //INST, not '"
                                                         << std::string(l.substr(0, 30)) << "'");
    } else if (section == Section::kPos) {
      if (u.compare(0, 3, "///") == 0) {
        ReadJbiPosHeader(&job, l, file, line);
      } else {
        ReadJbiPosition(&job, l, file, line);
      }
    } else {
      job.inst.push_back({std::string(l), line});
    }
  }
  WAAM_THROW_UNLESS(section != Section::kNone, file << ": not a JBI job (no /JOB line)");
  WAAM_THROW_UNLESS(section != Section::kPos,
                    file << ":" << lines.size() << ": the job ends inside //POS (no //INST): it is truncated");
  return job;
}

// What runs while //INST executes.
struct JbiRun {
  const std::string& file;
  const JbiReadOptions& options;
  const ProgramFrames& frames;
  const JbiJob& job;
  ParsedProgram& program;
  internal::WarningList& warnings;
  bool arc_on = false;
  double v_mm_s = 0.0;                           // the last V= (INFORM keeps the speed of the previous move)
  const JbiPosition* pending_station = nullptr;  // a station-only move's position, for the next robot move
  std::vector<ProgramMotion> circle;             // MOVC points waiting for the rest of their circle
};

// The MOVC points gathered: the circle's first point is reached by a linear move (none when the robot already
// stands there, the usual case), then (via, end) pairs; a point left over is followed linearly.
void FlushJbiCircle(JbiRun& run) {
  std::vector<ProgramMotion>& circle = run.circle;
  for (std::size_t k = 0; k < circle.size();) {
    if (k == 0 && circle.size() >= 3 && !run.program.motions.empty()) {
      const ProgramMotion& last = run.program.motions.back();
      if (last.has_pose && circle[0].has_pose && last.frame == circle[0].frame &&
          last.X_UT.isApprox(circle[0].X_UT, 1e-12)) {
        ++k;
        continue;
      }
    }
    if (k == 0 || k + 1 == circle.size()) {
      if (k > 0) run.warnings.Add("MOVC without the third point of its circle followed as a linear move", circle[k].line);
      circle[k].kind = MotionKind::kLinear;
      run.program.motions.push_back(circle[k]);
      ++k;
      continue;
    }
    ProgramMotion end = circle[k + 1];
    end.kind = MotionKind::kCircular;
    end.has_via = true;
    end.via = circle[k].X_UT.translation();
    WAAM_THROW_UNLESS(circle[k].has_pose && end.has_pose && circle[k].frame == end.frame,
                      run.file << ":" << circle[k].line << ": MOVC through a pulse position and a Cartesian one, "
                               << "or positions in different frames");
    run.program.motions.push_back(end);
    k += 2;
  }
  circle.clear();
}

// A Cartesian position's frame: ROBOT / BASE the robot's frame; USER in user frame n: program.frames.uframe.n (in the
// robot frame: x, y, z mm, rx, ry, rz deg, R = Rz Ry Rx), else program.frame.user_frame_mm, else refused. Its tool:
// ///TOOL n from program.frames.utool.n (no utool table: the cell's torch; a table without n: refused).
void SetJbiFrameAndTool(const JbiRun& run, const JbiPosition& p, int line, ProgramMotion* m) {
  m->frame = TargetFrame::kRobot;
  if (p.type == JbiPosType::kUser) {
    const auto f = run.frames.uframe.find(p.user);
    if (f != run.frames.uframe.end()) {
      const std::array<double, 6>& v = f->second;
      m->X_UT = internal::PoseXyzAbc(v[0], v[1], v[2], v[5], v[4], v[3]) * m->X_UT;
    } else {
      WAAM_THROW_UNLESS(run.frames.user_frame,
                        run.file << ":" << line << ": a position taught in user frame " << p.user
                                 << ", which the job does not define: give program.frames.uframe." << p.user
                                 << " = [x, y, z, rx, ry, rz] (mm, deg, in the robot frame)");
      m->frame = TargetFrame::kUser;
    }
  }
  if (p.tool < 0 || run.frames.utool.empty()) return;
  const auto t = run.frames.utool.find(p.tool);
  WAAM_THROW_UNLESS(t != run.frames.utool.end(),
                    run.file << ":" << line << ": a position taught with tool " << p.tool
                             << ", which the job does not define: give program.frames.utool." << p.tool
                             << " = [x, y, z, rx, ry, rz] (mm, deg, in the flange frame) or torch (the cell's)");
  m->tool_name = "TOOL " + std::to_string(p.tool);
  if (!t->second) return;
  const std::array<double, 6>& v = *t->second;
  m->has_tool = true;
  m->X_FT = internal::PoseXyzAbc(v[0], v[1], v[2], v[5], v[4], v[3]);
}

// The robot position of a move: pulses through the arm's pulses per degree, or X, Y, Z, Rx, Ry, Rz.
void SetJbiRobotTarget(const JbiRun& run, const JbiPosition& p, int line, ProgramMotion* m) {
  if (p.type == JbiPosType::kPulse) {
    static const char* const kAxes[6] = {"S", "L", "U", "R", "B", "T"};
    for (int j = 0; j < 6; ++j) {
      const double ppd = run.options.robot_pulses_per_deg[j];
      WAAM_THROW_UNLESS(ppd > 0.0, run.file << ":" << p.line << ": a pulse position and the robot's pulses per "
                                            << "degree are unknown (axis " << kAxes[j]
                                            << "): give program.yaskawa.pulses_per_deg [S, L, U, R, B, T] or "
                                            << "--pulses-per-deg");
      m->q[j] = p.values[j] / ppd / kDeg;
    }
    m->has_joints = true;
    return;
  }
  m->has_pose = true;
  // Rx, Ry, Rz: fixed angles about x, then y, then z: R = Rz Ry Rx.
  m->X_UT.translation() = Eigen::Vector3d(p.values[0], p.values[1], p.values[2]);
  m->X_UT.linear() = internal::RotationZyx(p.values[5] / kDeg, p.values[4] / kDeg, p.values[3] / kDeg);
  m->config = p.config;
  SetJbiFrameAndTool(run, p, line, m);
}

// The station position (EC, EX): tilt and rotation through the station's pulses per degree.
void SetJbiStation(const JbiRun& run, const JbiPosition& station, ProgramMotion* m) {
  WAAM_THROW_UNLESS(station.values.size() >= 2, run.file << ":" << station.line << ": a station position needs two "
                                                         << "axes (tilt, rotation), " << station.values.size()
                                                         << " given");
  const double tp = run.options.station_pulses_per_deg[0], rp = run.options.station_pulses_per_deg[1];
  WAAM_THROW_UNLESS(tp > 0.0 && rp > 0.0,
                    run.file << ":" << station.line << ": station positions are encoder pulses and the station's "
                             << "pulses per degree are unknown: give program.yaskawa.station_pulses_per_deg "
                             << "[tilt, rotation] or --station-pulses-per-deg");
  m->has_positioner = true;
  m->tilt_rad = station.values[0] / tp / kDeg;
  m->rotation_rad = station.values[1] / rp / kDeg;
}

// A move's tags: position variables, speeds (V=, VJ=, VR=...), blending and conditions; `robot` / `station`
// receive the positions named.
void ReadJbiMoveTags(JbiRun& run, TokenCursor& ts, const std::string& word, const JbiPosition** robot,
                     const JbiPosition** station) {
  while (!ts.AtEnd()) {
    if (ts.Accept("+")) continue;  // +MOVJ: a second group's move on the same line
    const std::string tag = ts.Peek().kind == TokenKind::kWord ? ts.Next().text : ts.Next().raw;
    int kind = -1;
    long index = 0;
    if (SplitPositionName(tag, &kind, &index)) {
      const auto found = run.job.positions[kind].find(index);
      if (found == run.job.positions[kind].end()) ts.Fail(tag + " is used but not defined in //POS");
      if (kind == 0 || kind == 3) *robot = &found->second;
      if (kind == 2 || kind == 5) *station = &found->second;
      if (kind == 1 || kind == 4) {
        run.warnings.Add("base axis positions (" + std::string(kKinds[kind]) + ") not executed: the cell has no "
                         "travelling base", ts.line());
      }
    } else if (tag == "V" && ts.Accept("=")) {
      if (!ts.PeekNumber()) {
        run.warnings.Add("speed from a variable (V=" + ts.Peek().raw.substr(0, 8) + "): the scenario's speed used",
                         ts.line());
        ts.Next();
        run.v_mm_s = 0.0;
        continue;
      }
      run.v_mm_s = ts.ExpectNumber("V=");
      if (run.v_mm_s <= 0.0) ts.Fail("V= must be > 0 mm/s");
    } else if (tag == "VJ" || tag == "PL" || tag == "CR" || tag == "ACC" || tag == "DEC" || tag == "VR" ||
               tag == "VE" || tag == "FPT" || tag == "NWAIT" || tag == "MOVJ" || tag == "MOVL") {
      if (ts.Accept("=")) ts.Next();  // joint speed %, blending, accelerations: no effect on the path's points
    } else if (tag.front() == 'L' && tag.size() > 1 && std::isalpha(static_cast<unsigned char>(tag[1]))) {
      ts.Fail(word + " to a local position variable " + tag + ", which the job does not define");
    } else {
      // UNTIL IN#(n)=ON, ENWAIT, a condition: not executed, with the rest of the line.
      run.warnings.Add(word + " option " + tag.substr(0, 16) + " not executed", ts.line());
      break;
    }
  }
}

// MOVJ / MOVL / MOVC / MOVS: positions, speed, the arc in force; MOVC points gather into circles.
void ExecJbiMove(JbiRun& run, TokenCursor& ts, const std::string& word) {
  const int line = ts.line();
  if (word == "MOVS") run.warnings.Add("MOVS (spline) followed as linear moves through its points", line);
  internal::CheckMotionCount(run.program.motions.size() + run.circle.size(), run.file, line);
  const JbiPosition* robot = nullptr;
  const JbiPosition* station = nullptr;
  const double v_before = run.v_mm_s;
  ReadJbiMoveTags(run, ts, word, &robot, &station);
  WAAM_THROW_UNLESS(robot != nullptr || station != nullptr,
                    run.file << ":" << line << ": " << word << " needs a position (C00000)");
  if (robot == nullptr) {
    run.warnings.Add("station-only move not executed alone: its angles are taken by the next robot move", line);
    run.pending_station = station;
    return;
  }
  ProgramMotion m;
  m.line = line;
  m.kind = word == "MOVJ" ? MotionKind::kJoint : MotionKind::kLinear;
  if (station == nullptr) station = run.pending_station;
  run.pending_station = nullptr;
  if (station != nullptr) SetJbiStation(run, *station, &m);
  if (station != nullptr && station->values.size() > 2) {
    run.warnings.Add("station axes past the second not executed", station->line);
  }
  SetJbiRobotTarget(run, *robot, line, &m);
  if (word != "MOVJ" && run.v_mm_s <= 0.0 && v_before <= 0.0) {
    run.warnings.Add(word + " before any V=: the scenario's speed used", line);
  }
  m.speed_mm_s = word == "MOVJ" ? 0.0 : run.v_mm_s;
  m.weld = run.arc_on && word != "MOVJ";
  if (word == "MOVC") {
    run.circle.push_back(m);
  } else {
    run.program.motions.push_back(m);
  }
}

// A time tag T=t (s) of TIMER, ARCON (the time at the start point) or ARCOF (crater fill): the torch waits at its last
// target; a time from a variable is warned.
void ExecJbiTime(JbiRun& run, TokenCursor& ts, const std::string& word, bool required) {
  while (!ts.AtEnd() && !(ts.Is("T") && ts.Is("=", 1))) ts.Next();
  if (ts.AtEnd()) {
    if (required) ts.Fail(word + " without its T=");
    return;
  }
  ts.Next(), ts.Next();
  if (!ts.PeekNumber()) {
    run.warnings.Add(word + " T= of a variable not in the timeline", ts.line());
    return;
  }
  const double t = ts.ExpectNumber(word + " T");
  if (t < 0.0) ts.Fail(word + " T=" + std::to_string(t) + " must be >= 0");
  internal::AddDwell(&run.program.motions, t, ts.line(), &run.warnings);
}

// One //INST line.
void ExecJbiInst(JbiRun& run, const JbiInstLine& inst) {
  TokenCursor ts(inst.text, run.file, inst.line);
  if (ts.Is("/") || ts.Peek().kind == TokenKind::kString || ts.Is("*")) return;  // ///DATE.., 'comment, *label
  ts.Accept("+");
  const std::string word = ts.ExpectWord("an instruction");
  if (word != "MOVC") FlushJbiCircle(run);
  if (word == "MOVJ" || word == "MOVL" || word == "MOVC" || word == "MOVS") {
    ExecJbiMove(run, ts, word);
  } else if (word == "ARCON" || word == "ARCOF") {
    // ARCON [ASF#(n) | AC= AV= AVP= T=]: the arc strikes at the robot's position; ARCOF [AEF#(n) | AC= AV= T=].
    run.arc_on = word == "ARCON";
    ExecJbiTime(run, ts, word, false);
  } else if (word == "TIMER") {
    ExecJbiTime(run, ts, word, true);
  } else if (word != "NOP") {
    const bool weave = word == "WVON" || word == "WVOF";
    run.warnings.Add("instruction " + word.substr(0, 24) + " not executed" + (weave ? ": one bead along the path" : ""),
                     inst.line);
  }
}

}  // namespace

ParsedProgram ReadYaskawaJbi(std::string_view text, const std::string& file, const JbiReadOptions& options,
                             const ProgramFrames& frames) {
  ParsedProgram program;
  program.format = ProgramFormat::kYaskawaJbi;
  internal::WarningList warnings;
  const std::vector<std::string_view> lines = internal::SplitProgramLines(text, file);
  const JbiJob job = ReadJbiSections(lines, file);
  program.name = job.name;
  JbiRun run{file, options, frames, job, program, warnings, false, 0.0, nullptr, {}};
  bool ended = false;
  for (const JbiInstLine& inst : job.inst) {
    if (Upper(inst.text) == "END") {
      ended = true;
      break;
    }
    ExecJbiInst(run, inst);
  }
  FlushJbiCircle(run);
  WAAM_THROW_UNLESS(ended, file << ":" << lines.size() << ": no END: the job is truncated");
  program.warnings = warnings.Take();
  return program;
}

}  // namespace waam::planner
