// FANUC LS (ASCII teach-pendant program) reader: the sections split into /MN statements (numbered or not, broken
// over continuation lines) and /POS positions, each statement tokenized and run by a small function of its kind.
#include <cctype>
#include <cmath>
#include <map>

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

struct LsPosition {
  int line = 0;
  bool cartesian = false;     // GP1 X Y Z W P R
  double xyzwpr[6] = {0, 0, 0, 0, 0, 0};
  int xyzwpr_seen = 0;        // bit per value
  bool joints = false;        // GP1 J1..J6
  double j[6] = {0, 0, 0, 0, 0, 0};
  int j_seen = 0;
  int config = -1;
  bool gp2 = false;
  double gp2_j[2] = {0, 0};
  int gp2_seen = 0;
  int uf = -1;                // GP1 UF and UT (-1: not given)
  int ut = -1;
};

struct LsStatement {
  std::string text;  // without its line number and closing ';'
  int line = 0;
};

// The program's sections as read.
struct LsSource {
  std::string name;
  std::vector<LsStatement> statements;
  std::map<int, LsPosition> positions;
};

// What runs while the /MN statements are executed.
struct LsRun {
  const std::string& file;
  const ProgramFrames& frames;
  const std::map<int, LsPosition>& positions;
  ParsedProgram& program;
  internal::WarningList& warnings;
  bool arc_on = false;
  int uframe_num = -1;  // UFRAME_NUM / UTOOL_NUM set by the program (-1: the controller's, unknown)
  int utool_num = -1;
};

// "N U T, 0, 0, 0" -> branch bits (bit 0 back, bit 1 elbow down, bit 2 wrist flipped), as FanucConfig writes them.
int ParseLsConfig(const std::string& text, const std::string& file, int line) {
  const std::string u = Upper(text);
  int bits = 0, letters = 0;
  for (char c : u.substr(0, u.find(','))) {
    if (c == ' ') continue;
    ++letters;
    if (c == 'F') bits |= 4;
    else if (c == 'D') bits |= 2;
    else if (c == 'B') bits |= 1;
    else WAAM_THROW_UNLESS(c == 'N' || c == 'U' || c == 'T', file << ":" << line << ": CONFIG '" << text
                                                                << "': expected letters N/F, U/D, T/B");
  }
  WAAM_THROW_UNLESS(letters == 3, file << ":" << line << ": CONFIG '" << text
                                       << "': expected three letters (wrist N/F, elbow U/D, base T/B)");
  return bits;
}

// One /POS group line: "UF : 1, UT : 1, CONFIG : '...'," or "X = 1.0 mm, Y = ..." or "J1 = 0.0 deg, ...".
void ReadLsGroupLine(TokenCursor& ts, int group, LsPosition* pos, internal::WarningList* warnings) {
  static const char* const kCart[6] = {"X", "Y", "Z", "W", "P", "R"};
  while (!ts.AtEnd()) {
    if (ts.Accept(",")) continue;
    const std::string key = ts.ExpectWord("a /POS item KEY = value");
    if (ts.Accept(":")) {
      if (key == "CONFIG") {
        if (ts.Peek().kind != TokenKind::kString) ts.Fail("CONFIG without its quoted string");
        pos->config = ParseLsConfig(ts.Next().text, ts.file(), ts.line());
      } else if ((key == "UF" || key == "UT") && group == 1) {
        (key == "UF" ? pos->uf : pos->ut) = ts.ExpectInteger(key, 0, 999);
      } else {
        ts.Next();  // UF / UT of another group: the positioner's frame is the cell's
      }
      continue;
    }
    if (!ts.Accept("=")) ts.Fail("/POS item '" + key + "' is not KEY = value");
    const double v = ts.ExpectNumber(key);
    if (ts.Is("MM") || ts.Is("DEG")) ts.Next();
    bool used = false;
    for (int k = 0; k < 6 && group == 1; ++k) {
      if (key != kCart[k]) continue;
      pos->cartesian = true, pos->xyzwpr[k] = v, pos->xyzwpr_seen |= 1 << k, used = true;
    }
    if (group == 1 && key.size() == 2 && key[0] == 'J' && key[1] >= '1' && key[1] <= '6') {
      pos->joints = true, pos->j[key[1] - '1'] = v, pos->j_seen |= 1 << (key[1] - '1'), used = true;
    }
    if (group == 2 && (key == "J1" || key == "J2")) {
      pos->gp2 = true, pos->gp2_j[key[1] - '1'] = v, pos->gp2_seen |= 1 << (key[1] - '1'), used = true;
    }
    if (!used) {
      warnings->Add(group == 1 ? "GP1 extended axis " + key + " ignored"
                               : "motion group GP" + std::to_string(group) + " axis " + key + " ignored",
                    ts.line());
    }
  }
}

// "P[12]", "P[12:comment]" or "PR[3]" at the cursor; the number, `*register_ref` when PR; -1 when none is there.
int ReadLsPositionRef(TokenCursor& ts, bool* register_ref) {
  if (!(ts.Is("P") || ts.Is("PR")) || !ts.Is("[", 1)) return -1;
  *register_ref = ts.Next().text == "PR";
  ts.Next();
  if (*register_ref && ts.Is("GP1") && ts.Is(":", 1)) ts.Next(), ts.Next();  // PR[GP1:3]
  const int number = ts.ExpectInteger(*register_ref ? "PR number" : "P number", 1, 99999);
  while (!ts.AtEnd() && !ts.Is("]")) ts.Next();  // ":comment"
  ts.Expect("]", "position");
  return number;
}

// The lines of a P[n]{ ... }; entry, from the line after its head to its "};".
LsPosition ReadLsPosition(const std::vector<std::string_view>& lines, std::size_t* li, int number,
                          const std::string& file, internal::WarningList* warnings) {
  LsPosition pos;
  pos.line = static_cast<int>(*li) + 1;
  int group = 0;
  for (++*li; *li < lines.size(); ++*li) {
    const int pl = static_cast<int>(*li) + 1;
    const std::string_view body = TrimBlank(lines[*li]);
    if (body.empty()) continue;
    if (body == "};") break;
    WAAM_THROW_UNLESS(body.front() != '/',
                      file << ":" << pl << ": P[" << number << "] in /POS is not closed by '};' (truncated /POS)");
    TokenCursor ts(body, file, pl);
    if (ts.Peek().kind == TokenKind::kWord && ts.Peek().text.compare(0, 2, "GP") == 0 && ts.Is(":", 1)) {
      const std::string gp = ts.Peek().text.substr(2);
      group = internal::ParseProgramInteger(gp, file, pl, "motion group", 1, 8);
      ts.Next(), ts.Next();
      if (ts.AtEnd()) continue;
    }
    WAAM_THROW_UNLESS(group > 0, file << ":" << pl << ": P[" << number << "] value before its GP1: line");
    ReadLsGroupLine(ts, group, &pos, warnings);
  }
  WAAM_THROW_UNLESS(*li < lines.size(), file << ":" << pos.line << ": P[" << number
                                              << "] in /POS is not closed by '};' (truncated /POS)");
  WAAM_THROW_UNLESS(!pos.cartesian || pos.xyzwpr_seen == 63,
                    file << ":" << pos.line << ": P[" << number << "] lacks one of X, Y, Z, W, P, R");
  WAAM_THROW_UNLESS(!pos.joints || pos.j_seen == 63,
                    file << ":" << pos.line << ": P[" << number << "] lacks one of J1..J6");
  WAAM_THROW_UNLESS(pos.cartesian != pos.joints,
                    file << ":" << pos.line << ": P[" << number << "] needs GP1 as X..R or as J1..J6");
  WAAM_THROW_UNLESS(!pos.gp2 || (pos.gp2_seen & 1), file << ":" << pos.line << ": P[" << number << "] GP2 needs J1");
  return pos;
}

// One /MN line: "  12:  L P[3] ... ;" (numbered), "    :  P[5] ... ;" (continuation) or "L P[3] ... ;" (written
// without line numbers, as hand-edited and exported programs are; such a line without its ';' goes on below).
void AddLsMnLine(std::string_view raw, int line, const std::string& file, std::vector<LsStatement>* statements,
                 bool* open) {
  std::string_view t = TrimBlank(raw);
  std::size_t digits = 0;
  while (digits < t.size() && std::isdigit(static_cast<unsigned char>(t[digits]))) ++digits;
  const std::string_view after = TrimBlank(t.substr(digits));
  const bool numbered = digits > 0 && !after.empty() && after.front() == ':';
  const bool continuation = digits == 0 && t.front() == ':';
  if (numbered || continuation) t = TrimBlank(after.empty() ? after : after.substr(1));
  if (continuation) {
    WAAM_THROW_UNLESS(*open, file << ":" << line << ": continuation line without a statement before it");
  } else if (numbered) {
    WAAM_THROW_UNLESS(!*open, file << ":" << statements->back().line << ": statement without its closing ';'");
  }
  if (numbered || !*open) {
    internal::CheckMotionCount(statements->size(), file, line);
    statements->push_back({"", line});
  } else {
    statements->back().text += ' ';
  }
  *open = true;
  if (!t.empty() && t.back() == ';') {
    t.remove_suffix(1);
    *open = false;
  }
  statements->back().text += std::string(TrimBlank(t));
}

// The sections /PROG, /ATTR, /APPL, /MN, /POS, /END.
LsSource ReadLsSections(const std::vector<std::string_view>& lines, const std::string& file,
                        internal::WarningList* warnings) {
  LsSource src;
  enum class Section { kNone, kHeader, kMn, kPos, kEnd } section = Section::kNone;
  bool open = false;
  for (std::size_t li = 0; li < lines.size(); ++li) {
    const int line = static_cast<int>(li) + 1;
    const std::string_view t = TrimBlank(lines[li]);
    if (t.empty()) continue;
    if (t.front() == '/' && (t.size() < 2 || t[1] != '/')) {
      const std::string head = Upper(t.substr(0, std::min(t.find_first_of(" \t"), t.size())));
      if (head == "/PROG" && section == Section::kNone) {
        section = Section::kHeader;
        src.name = std::string(TrimBlank(t.substr(5)));
        src.name = src.name.substr(0, src.name.find_first_of(" \t"));
        continue;
      }
      WAAM_THROW_UNLESS(section != Section::kNone, file << ":" << line << ": expected /PROG <name> before " << head);
      WAAM_THROW_UNLESS(section != Section::kEnd, file << ":" << line << ": text after /END");
      if (head == "/ATTR" || head == "/APPL") section = Section::kHeader;
      else if (head == "/MN") section = Section::kMn;
      else if (head == "/POS") section = Section::kPos;
      else if (head == "/END") section = Section::kEnd;
      else WAAM_THROW(file << ":" << line << ": unknown section " << head);
      continue;
    }
    WAAM_THROW_UNLESS(section != Section::kNone, file << ":" << line << ": expected /PROG <name> as the first line");
    if (section == Section::kMn) {
      AddLsMnLine(lines[li], line, file, &src.statements, &open);
    } else if (section == Section::kPos) {
      TokenCursor ts(t, file, line);
      bool is_register = false;
      const int number = ReadLsPositionRef(ts, &is_register);
      WAAM_THROW_UNLESS(number > 0 && !is_register && ts.Accept("{") && ts.AtEnd(),
                        file << ":" << line << ": /POS expected 'P[n]{', got '" << std::string(t.substr(0, 40)) << "'");
      WAAM_THROW_UNLESS(src.positions.count(number) == 0, file << ":" << line << ": P[" << number << "] defined twice");
      internal::CheckMotionCount(src.positions.size(), file, line);
      src.positions[number] = ReadLsPosition(lines, &li, number, file, warnings);
    } else if (section == Section::kEnd) {
      WAAM_THROW(file << ":" << line << ": text after /END");
    }
    // /ATTR and /APPL: header data the motion does not depend on.
  }
  WAAM_THROW_UNLESS(section != Section::kNone, file << ": not a FANUC LS program (no /PROG line)");
  WAAM_THROW_UNLESS(section == Section::kEnd, file << ":" << lines.size() << ": no /END: the program is truncated");
  WAAM_THROW_UNLESS(!open, file << ":" << src.statements.back().line << ": statement without its closing ';'");
  return src;
}

// A register's text "R[5]" / "AR[1]" / "R[R[2]]" at the cursor (its name already read).
std::string ReadLsRegister(TokenCursor& ts, const std::string& name) {
  std::string text = name + "[";
  int depth = 0;
  do {
    const internal::Token& t = ts.Next();
    if (t.kind == TokenKind::kEnd) ts.Fail(name + "[ without its ']'");
    if (t.text == "[") ++depth;
    if (t.text == "]") --depth;
    if (depth > 0 && t.text != "[") text += t.text;
  } while (depth > 0);
  return text + "]";
}

// A speed unit: "%", "mm/sec", "cm/min", "inch/min", "deg/sec", "sec", "msec" (upper case), or "".
std::string ReadLsSpeedUnit(TokenCursor& ts) {
  if (ts.Accept("%")) return "%";
  if (ts.Peek().kind != TokenKind::kWord) return "";
  if (ts.Is("/", 1)) {
    std::string unit = ts.Next().text + "/";
    ts.Next();
    if (ts.Peek().kind == TokenKind::kWord) unit += ts.Next().text;
    return unit;
  }
  if (ts.Is("SEC") || ts.Is("MSEC")) return ts.Next().text;
  return "";
}

// The speed of a motion, mm/s (0: none in the program: the scenario's, with a warning). Forms: a number with its
// unit, R[n] or AR[n] with a unit (a register), WELD_SPEED (the weld schedule's), MAX_SPEED.
double ReadLsSpeed(LsRun& run, TokenCursor& ts, MotionKind kind) {
  const int line = ts.line();
  if (ts.Accept("WELD_SPEED")) {
    run.warnings.Add("speed WELD_SPEED from the weld schedule: the scenario's process.travel_speed_mm_min used", line);
    return 0.0;
  }
  if (ts.Accept("MAX_SPEED")) return 0.0;
  if ((ts.Is("R") || ts.Is("AR")) && ts.Is("[", 1)) {
    const std::string reg = ReadLsRegister(ts, ts.Next().text);
    ReadLsSpeedUnit(ts);
    run.warnings.Add("speed from a register (" + reg + "): the scenario's speed used", line);
    return 0.0;
  }
  if (ts.Peek().kind != TokenKind::kNumber) {
    ts.Fail("motion speed '" + ts.Rest() + "' has no number and unit");
  }
  const double v = ts.Next().number;
  const std::string unit = ReadLsSpeedUnit(ts);
  if (unit == "%" || unit == "SEC" || unit == "MSEC" || unit == "DEG/SEC") {
    if (kind != MotionKind::kJoint) {
      run.warnings.Add("speed " + unit + " of a Cartesian move: the scenario's speed used", line);
    }
    return 0.0;
  }
  WAAM_THROW_UNLESS(!unit.empty(), ts.file() << ":" << line << ": motion speed '" << v << "' has no unit");
  WAAM_THROW_UNLESS(v > 0.0, ts.file() << ":" << line << ": motion speed " << v << unit << " must be > 0");
  if (unit == "MM/SEC") return v;
  if (unit == "CM/MIN") return v * 10.0 / 60.0;
  if (unit == "INCH/MIN") return v * 25.4 / 60.0;
  ts.Fail("motion speed unit '" + unit + "' unknown");
}

// The termination: FINE, CNT n, CNT R[n], CD n, CR n (the path runs through the point either way here).
void ReadLsTermination(TokenCursor& ts) {
  const std::string& w = ts.Peek().text;
  if (ts.Peek().kind == TokenKind::kWord &&
      (w == "FINE" || w.compare(0, 3, "CNT") == 0 || w.compare(0, 2, "CD") == 0 || w.compare(0, 2, "CR") == 0)) {
    ts.Next();
    if ((ts.Is("R") || ts.Is("AR")) && ts.Is("[", 1)) ReadLsRegister(ts, ts.Next().text);
    return;
  }
  ts.Fail("motion without its termination (FINE, CNT n, CD n or CR n) at '" + ts.Rest() + "'");
}

// Motion options after the termination: Arc Start[..] / Arc End[..] switch the arc; COORD, PTH and BREAK change
// nothing here; Weave and everything else (Offset,PR[n], Tool_Offset, INC, ACC, Skip, TB/TA/DB ...) is warned.
void ReadLsMotionOptions(LsRun& run, TokenCursor& ts, bool* arc_start, bool* arc_end) {
  while (!ts.AtEnd()) {
    if (ts.Peek().kind != TokenKind::kWord) {
      if (!ts.SkipGroup()) ts.Next();
      continue;
    }
    const std::string word = ts.Next().text;
    if (word == "ARC" && (ts.Is("START") || ts.Is("END"))) {
      (ts.Next().text == "START" ? *arc_start : *arc_end) = true;
      ts.SkipGroup();
      continue;
    }
    if (word == "COORD" || word == "PTH" || word == "BREAK") continue;
    if (word == "WEAVE") {
      run.warnings.Add("instruction WEAVE not executed: one bead along the path", ts.line());
      while (!ts.AtEnd() && !ts.Is("[")) ts.Next();
      ts.SkipGroup();
      continue;
    }
    run.warnings.Add("motion option " + word.substr(0, 24) + " not executed", ts.line());
    if (ts.PeekNumber()) {
      // TB / TA / DB <time or distance>, <action>: the action runs to the end of the statement.
      ts.ExpectNumber(word);
      ReadLsSpeedUnit(ts);
      if (ts.Is("MM")) ts.Next();
      while (!ts.AtEnd()) ts.Next();
    } else if (ts.Accept(",")) {
      ts.Accept("PR");
      ts.Accept("LBL");
      ts.SkipGroup();
    } else {
      ts.SkipGroup();
    }
  }
}

// The pose of a frame or tool given in the scenario as x, y, z, w, p, r (mm, deg).
Eigen::Isometry3d LsFramePose(const std::array<double, 6>& f) {
  return internal::PoseXyzAbc(f[0], f[1], f[2], f[5], f[4], f[3]);
}

// The frame a Cartesian position is taught in and the tool it is taught with: UF 0 is the world, UF n the
// scenario's program.frames.uframe.n (else program.frame.user_frame_mm, the program's one user frame), UT n the
// scenario's program.frames.utool.n (UT 0 the faceplate; no utool table at all: the cell's torch). Refuses a frame,
// or a tool missing from a utool table, that the scenario does not give, and a UF / UT other than the UFRAME_NUM /
// UTOOL_NUM the program set (the controller stops there).
void SetLsFrameAndTool(LsRun& run, const LsPosition& pos, int number, int line, ProgramMotion* m) {
  const int uf = pos.uf >= 0 ? pos.uf : std::max(run.uframe_num, 0);
  const int ut = pos.ut >= 0 ? pos.ut : run.utool_num;
  WAAM_THROW_UNLESS(run.uframe_num < 0 || pos.uf < 0 || pos.uf == run.uframe_num,
                    run.file << ":" << line << ": P[" << number << "] is taught in UF " << pos.uf
                             << " but UFRAME_NUM is " << run.uframe_num << ": the controller stops at this motion");
  WAAM_THROW_UNLESS(run.utool_num < 0 || pos.ut < 0 || pos.ut == run.utool_num,
                    run.file << ":" << line << ": P[" << number << "] is taught with UT " << pos.ut
                             << " but UTOOL_NUM is " << run.utool_num << ": the controller stops at this motion");
  if (m->has_pose) {
    const auto frame = run.frames.uframe.find(uf);
    if (uf == 0) {
      m->frame = TargetFrame::kArmWorld;
    } else if (frame != run.frames.uframe.end()) {
      m->frame = TargetFrame::kArmWorld;
      m->X_UT = LsFramePose(frame->second) * m->X_UT;
    } else {
      WAAM_THROW_UNLESS(run.frames.user_frame,
                        run.file << ":" << line << ": P[" << number << "] is taught in user frame UF " << uf
                                 << ", which the program does not define: give program.frames.uframe." << uf
                                 << " = [x, y, z, w, p, r] (mm, deg, in the world frame)");
      m->frame = TargetFrame::kUser;
    }
  }
  // No tool named, or no tool table in the scenario: the cell's torch is the program's tool.
  if (ut < 0 || run.frames.utool.empty()) return;
  const auto tool = run.frames.utool.find(ut);
  WAAM_THROW_UNLESS(ut == 0 || tool != run.frames.utool.end(),
                    run.file << ":" << line << ": P[" << number << "] is taught with tool UT " << ut
                             << ", which the program does not define: give program.frames.utool." << ut
                             << " = [x, y, z, w, p, r] (mm, deg, in the flange frame) or torch (the cell's)");
  if (ut != 0 && !tool->second) return;
  m->has_tool = true;
  m->X_FT = ut == 0 ? Eigen::Isometry3d::Identity() : LsFramePose(*tool->second);
  m->tool_name = "UT " + std::to_string(ut);
}

// The target of a motion from /POS: pose or joints, positioner group GP2, frame and tool.
void SetLsTarget(LsRun& run, int number, int line, ProgramMotion* m) {
  const auto found = run.positions.find(number);
  WAAM_THROW_UNLESS(found != run.positions.end(),
                    run.file << ":" << line << ": P[" << number << "] is used but not defined in /POS");
  const LsPosition& pos = found->second;
  if (pos.cartesian) {
    m->has_pose = true;
    m->X_UT = internal::PoseXyzAbc(pos.xyzwpr[0], pos.xyzwpr[1], pos.xyzwpr[2], pos.xyzwpr[5], pos.xyzwpr[4],
                                   pos.xyzwpr[3]);
    m->config = pos.config;
  } else {
    m->has_joints = true;
    for (int j = 0; j < 6; ++j) m->q[j] = pos.j[j] * kPi / 180.0;
  }
  SetLsFrameAndTool(run, pos, number, line, m);
  if (pos.gp2) {
    // J1 and J2 of a two-axis positioner, or J1 alone of a turntable.
    m->has_positioner = true;
    m->positioner_numbered = true;
    m->tilt_rad = pos.gp2_j[0] * kPi / 180.0;
    m->rotation_rad = pos.gp2_j[1] * kPi / 180.0;
  }
}

// "J P[1] 30% FINE", "L P[2] 100mm/sec CNT100 Arc Start[1]", "C P[6] P[7] 40cm/min FINE" (the via point and the
// end), "A P[3] ..." (circular arc: warned). PR targets are warned (the register is not in the program).
void ExecLsMotion(LsRun& run, TokenCursor& ts, const std::string& letter) {
  const int line = ts.line();
  ProgramMotion m;
  m.line = line;
  m.kind = letter == "J" ? MotionKind::kJoint : (letter == "L" ? MotionKind::kLinear : MotionKind::kCircular);
  bool is_register = false;
  int target = ReadLsPositionRef(ts, &is_register);
  if (letter == "A") {
    run.warnings.Add("circular arc motion A not executed", line);
    return;
  }
  int via = -1;
  if (m.kind == MotionKind::kCircular) {
    via = target;
    bool end_register = false;
    target = ReadLsPositionRef(ts, &end_register);
    WAAM_THROW_UNLESS(target > 0, run.file << ":" << line << ": circular motion C needs its via and end positions");
    is_register = is_register || end_register;
  }
  if (is_register) {
    run.warnings.Add("motion to a position register PR[n] not executed", line);
    return;
  }
  internal::CheckMotionCount(run.program.motions.size(), run.file, line);
  m.speed_mm_s = ReadLsSpeed(run, ts, m.kind);
  ReadLsTermination(ts);
  bool arc_start = false, arc_end = false;
  ReadLsMotionOptions(run, ts, &arc_start, &arc_end);
  // Arc Start on a motion: the arc strikes at its end point; Arc End: the move welds, the arc ends at its end.
  m.weld = arc_start ? false : run.arc_on;
  if (arc_start) run.arc_on = true;
  if (arc_end) m.weld = true, run.arc_on = false;
  SetLsTarget(run, target, line, &m);
  if (via > 0) {
    const auto v = run.positions.find(via);
    WAAM_THROW_UNLESS(v != run.positions.end(),
                      run.file << ":" << line << ": P[" << via << "] is used but not defined in /POS");
    WAAM_THROW_UNLESS(v->second.cartesian,
                      run.file << ":" << line << ": the via point P[" << via << "] of a C motion must be Cartesian");
    ProgramMotion via_motion;
    via_motion.has_pose = true;
    SetLsTarget(run, via, line, &via_motion);
    WAAM_THROW_UNLESS(via_motion.frame == m.frame && (via_motion.frame != TargetFrame::kArmWorld ||
                                                      v->second.uf == run.positions.at(target).uf),
                      run.file << ":" << line << ": the via point P[" << via << "] is in another user frame");
    m.has_via = true;
    m.via = via_motion.X_UT.translation();
  }
  run.program.motions.push_back(m);
}

// "WAIT 1.00(sec)": the torch waits at its last target; WAIT R[n] and WAIT <condition> are warned.
void ExecLsWait(LsRun& run, TokenCursor& ts) {
  if (ts.Peek().kind == TokenKind::kNumber) {
    const double s = ts.ExpectNumber("WAIT time");
    ts.Accept("(");
    const std::string unit = ts.Peek().kind == TokenKind::kWord ? ts.Next().text : "SEC";
    ts.Accept(")");
    WAAM_THROW_UNLESS(unit == "SEC" && ts.AtEnd(), ts.file() << ":" << ts.line() << ": WAIT " << s << "(" << unit
                                                             << ") must be WAIT t(sec)");
    internal::AddDwell(&run.program.motions, s, ts.line(), &run.warnings);
    return;
  }
  if (ts.Is("R") && ts.Is("[", 1)) {
    run.warnings.Add("WAIT R[n] (a time from a register) not in the timeline", ts.line());
    return;
  }
  run.warnings.Add("WAIT for a condition not executed", ts.line());
}

// UFRAME_NUM=n / UTOOL_NUM=n: the frame and tool the positions must be taught in; from a register: unknown.
void ExecLsFrameNumber(LsRun& run, TokenCursor& ts, const std::string& word) {
  ts.Expect("=", word);
  int& number = word == "UFRAME_NUM" ? run.uframe_num : run.utool_num;
  number = ts.PeekNumber() ? ts.ExpectInteger(word, 0, 999) : -1;
}

// Runs one /MN statement; false at END.
bool ExecLsStatement(LsRun& run, const LsStatement& st) {
  const std::string_view text = TrimBlank(st.text);
  if (text.empty() || text.front() == '!' || text.compare(0, 2, "//") == 0) return true;  // comment, disabled line
  TokenCursor ts(text, run.file, st.line);
  if (ts.Peek().kind != TokenKind::kWord) {
    run.warnings.Add("instruction " + ts.Rest().substr(0, 24) + " not executed", st.line);
    return true;
  }
  const std::string first = ts.Peek().text;
  if ((first == "J" || first == "L" || first == "C" || first == "A") && (ts.Is("P", 1) || ts.Is("PR", 1))) {
    ts.Next();
    ExecLsMotion(run, ts, first);
    return true;
  }
  ts.Next();
  if (first == "ARC" && (ts.Is("START") || ts.Is("END"))) {
    run.arc_on = ts.Next().text == "START";
  } else if (first == "WAIT") {
    ExecLsWait(run, ts);
  } else if (first == "UFRAME_NUM" || first == "UTOOL_NUM") {
    ExecLsFrameNumber(run, ts, first);
  } else if (first == "END") {
    return false;
  } else if (first == "LBL") {
    // a label does nothing by itself
  } else if (first == "WEAVE") {
    run.warnings.Add("instruction WEAVE not executed: one bead along the path", st.line);
  } else if (first.compare(0, 9, "MULTIPASS") == 0 || first.compare(0, 3, "MP_") == 0) {
    run.warnings.Add("multi-pass instruction " + first.substr(0, 24) + " not executed: the taught pass only",
                     st.line);
  } else if ((first == "UFRAME" || first == "UTOOL") && ts.Is("[")) {
    run.warnings.Add(first + "[n] set by the program not executed: program.frames." +
                         (first == "UFRAME" ? "uframe" : "utool") + " used",
                     st.line);
  } else {
    run.warnings.Add("instruction " + first.substr(0, 24) + " not executed", st.line);
  }
  return true;
}

}  // namespace

ParsedProgram ReadFanucLs(std::string_view text, const std::string& file, const ProgramFrames& frames) {
  const std::vector<std::string_view> lines = internal::SplitProgramLines(text, file);
  internal::WarningList warnings;
  const LsSource src = ReadLsSections(lines, file, &warnings);
  ParsedProgram program;
  program.format = ProgramFormat::kFanucLs;
  program.name = src.name;
  LsRun run{file, frames, src.positions, program, warnings, false, -1, -1};
  for (const LsStatement& st : src.statements) {
    if (!ExecLsStatement(run, st)) break;
  }
  program.warnings = warnings.Take();
  return program;
}

}  // namespace waam::planner
