// KUKA KRL reader: the .dat declarations, then the .src statements, each tokenized and run by a small function of
// its kind (motions, speeds, the frames and tools the program sets, arc switching, waits).
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

using KrlAggregate = std::map<std::string, double>;

struct KrlDecl {
  std::string type;  // E6POS, POS, E6AXIS, AXIS, FRAME, FDAT
  KrlAggregate value;
  int line = 0;
  std::string file;
};

// A frame or tool in force: none set by the program, a pose, or a BASE_DATA / TOOL_DATA number the program names.
struct KrlFrameInForce {
  bool set = false;
  std::optional<Eigen::Isometry3d> X;  // the pose; empty with `set`: data number `number` not defined in the program
  int number = -1;
};

// What runs while the .src statements are executed.
struct KrlRun {
  const std::string& file;
  const ProgramFrames& frames;
  std::map<std::string, KrlDecl> decls;
  std::map<int, Eigen::Isometry3d> base_data, tool_data;  // BASE_DATA[n] / TOOL_DATA[n] the program assigns
  ParsedProgram& program;
  internal::WarningList& warnings;
  bool arc_on = false;
  double vel_mm_s = 0.0;  // $VEL.CP
  KrlFrameInForce base, tool;
  std::string fdat;       // FDAT_ACT
};

// "{X 1.0,Y 2,A 90,...}" or "{E6POS: X 1.0, ...}": the numeric items (enum, string and nested values skipped).
KrlAggregate ReadKrlAggregate(TokenCursor& ts) {
  ts.Expect("{", "a KRL aggregate {X 1.0,Y 2.0,...}");
  if (ts.Peek().kind == TokenKind::kWord && ts.Is(":", 1)) ts.Next(), ts.Next();  // the type: FRAME:, E6POS:
  KrlAggregate out;
  while (!ts.Accept("}")) {
    if (ts.AtEnd()) ts.Fail("aggregate without its '}'");
    if (ts.Accept(",")) continue;
    const std::string key = ts.ExpectWord("an aggregate item NAME value");
    if (ts.Is("[") && ts.Is("]", 1)) ts.Next(), ts.Next();  // POINT2[] " "
    if (ts.PeekNumber()) {
      out[key] = ts.ExpectNumber(key);
      if (out.size() > 64) ts.Fail("aggregate with too many items");
    } else if (!ts.SkipGroup()) {
      const internal::Token& v = ts.Peek();
      if (v.kind == TokenKind::kEnd || ts.Is(",") || ts.Is("}")) ts.Fail("aggregate item " + key + " has no value");
      // An enum (#BASE), a boolean or a string; any other word where a literal stands is no number.
      if (v.kind == TokenKind::kWord && v.text.front() != '#' && v.text != "TRUE" && v.text != "FALSE") {
        ts.Fail(key + " '" + v.raw + "' is not a finite number");
      }
      ts.Next();
    }
  }
  return out;
}

double KrlGet(const KrlAggregate& a, const char* key, const std::string& file, int line, const char* what) {
  const auto found = a.find(key);
  WAAM_THROW_UNLESS(found != a.end(), file << ":" << line << ": " << what << " lacks " << key);
  return found->second;
}

Eigen::Isometry3d KrlPose(const KrlAggregate& a, const std::string& file, int line) {
  auto get = [&](const char* key) { return KrlGet(a, key, file, line, "position"); };
  return internal::PoseXyzAbc(get("X"), get("Y"), get("Z"), get("A"), get("B"), get("C"));
}

// "[GLOBAL] [DECL] TYPE NAME = {...}" -> name and declaration; false for other declarations or no value.
bool ReadKrlDecl(std::string_view text, const std::string& file, int line, std::string* name, KrlDecl* decl) {
  TokenCursor ts(text, file, line);
  ts.Accept("GLOBAL");
  ts.Accept("DECL");
  ts.Accept("GLOBAL");
  if (ts.Peek().kind != TokenKind::kWord) return false;
  const std::string type = ts.Next().text;
  if (type != "E6POS" && type != "POS" && type != "E6AXIS" && type != "AXIS" && type != "FRAME" && type != "FDAT") {
    return false;
  }
  if (ts.Peek().kind != TokenKind::kWord || !ts.Is("=", 1)) return false;  // declared without a value
  *name = ts.Next().text;
  ts.Next();
  decl->type = type;
  decl->value = ReadKrlAggregate(ts);
  decl->line = line;
  decl->file = file;
  return true;
}

// The .dat: its DECL lines (";" starts a comment, "&" lines are editor attributes).
std::map<std::string, KrlDecl> ReadKrlDat(std::string_view dat, const std::string& dat_file) {
  std::map<std::string, KrlDecl> decls;
  const std::vector<std::string_view> lines = internal::SplitProgramLines(dat, dat_file);
  for (std::size_t li = 0; li < lines.size(); ++li) {
    const std::string_view l = TrimBlank(lines[li].substr(0, lines[li].find(';')));
    if (l.empty() || l.front() == '&') continue;
    std::string name;
    KrlDecl decl;
    if (ReadKrlDecl(l, dat_file, static_cast<int>(li) + 1, &name, &decl)) {
      internal::CheckMotionCount(decls.size(), dat_file, static_cast<int>(li) + 1);
      decls[name] = std::move(decl);
    }
  }
  return decls;
}

// "BASE_DATA[n]" / "TOOL_DATA[n]" at the cursor (the name read): n.
int ReadKrlDataIndex(TokenCursor& ts, const std::string& name) {
  ts.Expect("[", name);
  const int n = ts.ExpectInteger(name + " index", 0, 1024);
  ts.Expect("]", name);
  return n;
}

// A frame value: an aggregate, $NULLFRAME, BASE_DATA[n] / TOOL_DATA[n] or a FRAME the program declares.
KrlFrameInForce ReadKrlFrameValue(KrlRun& run, TokenCursor& ts) {
  KrlFrameInForce f;
  f.set = true;
  if (ts.Is("{")) {
    f.X = KrlPose(ReadKrlAggregate(ts), ts.file(), ts.line());
  } else if (ts.Accept("$NULLFRAME")) {
    f.X = Eigen::Isometry3d::Identity();
  } else if (ts.Is("BASE_DATA") || ts.Is("TOOL_DATA")) {
    const std::string name = ts.Next().text;
    f.number = ReadKrlDataIndex(ts, name);
    const auto& data = name == "BASE_DATA" ? run.base_data : run.tool_data;
    if (const auto found = data.find(f.number); found != data.end()) f.X = found->second;
    if (f.number == 0) f.X = Eigen::Isometry3d::Identity();  // BASE_DATA[0] / TOOL_DATA[0]: world, flange
  } else {
    const std::string name = ts.ExpectWord("a frame");
    const auto found = run.decls.find(name);
    if (found == run.decls.end() || found->second.type != "FRAME") {
      ts.Fail(name + " is used as a frame but not declared as a FRAME in the .dat or the .src");
    }
    f.X = KrlPose(found->second.value, found->second.file, found->second.line);
  }
  return f;
}

// Applies the FDAT_ACT in force (its TOOL_NO and BASE_NO), as BAS(#PTP_PARAMS / #CP_PARAMS / #FRAMES) does.
void ApplyKrlFdat(KrlRun& run, TokenCursor& ts) {
  if (run.fdat.empty()) return;
  const auto found = run.decls.find(run.fdat);
  if (found == run.decls.end() || found->second.type != "FDAT") ts.Fail(run.fdat + " is not declared as an FDAT");
  const KrlAggregate& a = found->second.value;
  for (const char* key : {"BASE_NO", "TOOL_NO"}) {
    const auto n = a.find(key);
    if (n == a.end()) continue;
    const std::string text = std::string(key[0] == 'B' ? "BASE_DATA[" : "TOOL_DATA[") +
                             std::to_string(static_cast<int>(n->second)) + "]";
    TokenCursor value(text, ts.file(), ts.line());
    (key[0] == 'B' ? run.base : run.tool) = ReadKrlFrameValue(run, value);
  }
}

// BAS(#CP_PARAMS, v) / BAS(#VEL_CP, v): the path speed v (m/s); BAS(#TOOL, n) / BAS(#BASE, n): TOOL_DATA[n] /
// BASE_DATA[n]; #PTP_PARAMS, #CP_PARAMS and #FRAMES also take the tool and base of the FDAT_ACT.
void ExecKrlBas(KrlRun& run, TokenCursor& ts) {
  ts.Expect("(", "BAS");
  const std::string what = ts.ExpectWord("a BAS function (#INITMOV, #CP_PARAMS ...)");
  std::optional<double> value;
  if (ts.Accept(",") && ts.PeekNumber()) value = ts.ExpectNumber("BAS " + what);
  if (what == "#CP_PARAMS" || what == "#VEL_CP") {
    WAAM_THROW_UNLESS(value && *value > 0.0, ts.file() << ":" << ts.line() << ": BAS without its speed");
    run.vel_mm_s = 1000.0 * *value;
  }
  if (what == "#CP_PARAMS" || what == "#PTP_PARAMS" || what == "#FRAMES") ApplyKrlFdat(run, ts);
  if ((what == "#TOOL" || what == "#BASE") && value) {
    TokenCursor data((what == "#TOOL" ? "TOOL_DATA[" : "BASE_DATA[") + std::to_string(static_cast<int>(*value)) + "]",
                     ts.file(), ts.line());
    (what == "#TOOL" ? run.tool : run.base) = ReadKrlFrameValue(run, data);
  }
}

// "$VAR = value": $VEL.CP (m/s), $BASE, $TOOL, $OUT[n]; other system variables do not change the path.
void ExecKrlSystemAssign(KrlRun& run, TokenCursor& ts, const std::string& var) {
  std::string name = var;
  if (ts.Is("[") && ts.Peek(1).kind == TokenKind::kNumber) {
    name += "[" + std::to_string(ReadKrlDataIndex(ts, var)) + "]";
  } else if (ts.SkipGroup()) {
    name += "[n]";  // an index from a variable
  }
  ts.Expect("=", name);
  if (name == "$VEL.CP") {
    if (!ts.PeekNumber()) {
      run.warnings.Add("$VEL.CP from a variable: the scenario's speed used", ts.line());
      run.vel_mm_s = 0.0;
      return;
    }
    run.vel_mm_s = 1000.0 * ts.ExpectNumber("$VEL.CP");
    WAAM_THROW_UNLESS(run.vel_mm_s > 0.0, ts.file() << ":" << ts.line() << ": $VEL.CP must be > 0");
  } else if (name == "$BASE" || name == "$TOOL") {
    (name == "$BASE" ? run.base : run.tool) = ReadKrlFrameValue(run, ts);
  } else if (var == "$OUT") {
    const std::string v = ts.Peek().kind == TokenKind::kWord ? ts.Next().text : "";
    WAAM_THROW_UNLESS(v == "TRUE" || v == "FALSE", ts.file() << ":" << ts.line() << ": " << name
                                                             << " must be TRUE or FALSE");
    if (name == "$OUT[1]") {
      run.arc_on = v == "TRUE";
    } else {
      run.warnings.Add("output " + name + " not executed", ts.line());
    }
  }
  // $APO, $ACC, $VEL.ORI, $ORI_TYPE...: no effect on the path
}

// "BASE_DATA[n] = {FRAME: X ..}" / "TOOL_DATA[n] = {...}": a frame or tool the program defines.
void ExecKrlDataAssign(KrlRun& run, TokenCursor& ts, const std::string& name) {
  const int n = ReadKrlDataIndex(ts, name);
  ts.Expect("=", name);
  const KrlFrameInForce f = ReadKrlFrameValue(run, ts);
  WAAM_THROW_UNLESS(f.X.has_value(), ts.file() << ":" << ts.line() << ": " << name << "[" << n
                                               << "] is set from a frame the program does not define");
  (name == "BASE_DATA" ? run.base_data : run.tool_data)[n] = *f.X;
}

// The base a Cartesian target is in (mm, in R) and the tool, from what the program set: BASE_DATA[n] the program
// does not define comes from program.frames.uframe.n (else refused); TOOL_DATA[n] from program.frames.utool.n (no
// utool table: the cell's torch; a table without n: refused).
void SetKrlFrameAndTool(KrlRun& run, int line, ProgramMotion* m, Eigen::Isometry3d* X_RB, bool* in_base) {
  *in_base = run.base.set;
  *X_RB = Eigen::Isometry3d::Identity();
  if (run.base.set && run.base.X) *X_RB = *run.base.X;
  if (run.base.set && !run.base.X) {
    const auto f = run.frames.uframe.find(run.base.number);
    WAAM_THROW_UNLESS(f != run.frames.uframe.end(),
                      run.file << ":" << line << ": $BASE is BASE_DATA[" << run.base.number
                               << "], which the program does not define: give program.frames.uframe."
                               << run.base.number << " = [x, y, z, a, b, c] (mm, deg, in the robot's base frame)");
    *X_RB = internal::PoseXyzAbc(f->second[0], f->second[1], f->second[2], f->second[3], f->second[4], f->second[5]);
  }
  if (!run.tool.set) return;
  m->tool_name = run.tool.number >= 0 ? "TOOL_DATA[" + std::to_string(run.tool.number) + "]" : "$TOOL";
  if (run.tool.X) {
    m->has_tool = true, m->X_FT = *run.tool.X;
    return;
  }
  if (run.frames.utool.empty()) return;  // the cell's torch
  const auto t = run.frames.utool.find(run.tool.number);
  WAAM_THROW_UNLESS(t != run.frames.utool.end(),
                    run.file << ":" << line << ": $TOOL is TOOL_DATA[" << run.tool.number
                             << "], which the program does not define: give program.frames.utool." << run.tool.number
                             << " = [x, y, z, a, b, c] (mm, deg, in the flange frame) or torch (the cell's)");
  if (!t->second) return;
  const std::array<double, 6>& v = *t->second;
  m->has_tool = true, m->X_FT = internal::PoseXyzAbc(v[0], v[1], v[2], v[3], v[4], v[5]);
}

// A motion's target: a name declared in the .dat or the .src, or an aggregate; `storage` holds an aggregate's.
const KrlDecl& ReadKrlTarget(KrlRun& run, TokenCursor& ts, KrlDecl* storage) {
  if (ts.Is("{")) {
    storage->value = ReadKrlAggregate(ts);
    storage->type = storage->value.count("A1") ? "E6AXIS" : "E6POS";
    storage->line = ts.line();
    storage->file = run.file;
    return *storage;
  }
  const std::string name = ts.ExpectWord("a position");
  const auto found = run.decls.find(name);
  WAAM_THROW_UNLESS(found != run.decls.end() && found->second.type != "FDAT",
                    run.file << ":" << ts.line() << ": " << name << " is used but not declared in the .dat or the .src");
  return found->second;
}

// PTP / LIN / CIRC (and the spline SPTP / SLIN / SCIRC): targets, then approximation words.
void ExecKrlMotion(KrlRun& run, TokenCursor& ts, const std::string& word) {
  const int line = ts.line();
  const std::string kind = word[0] == 'S' ? word.substr(1) : word;
  internal::CheckMotionCount(run.program.motions.size(), run.file, line);
  ProgramMotion m;
  m.line = line;
  m.kind = kind == "PTP" ? MotionKind::kJoint : (kind == "LIN" ? MotionKind::kLinear : MotionKind::kCircular);
  KrlDecl storage[2];
  if (ts.AtEnd()) ts.Fail(word + " needs " + (kind == "CIRC" ? "an auxiliary and an end" : "a") + " position");
  const KrlDecl* aux = nullptr;
  if (kind == "CIRC") {
    aux = &ReadKrlTarget(run, ts, &storage[1]);
    if (!ts.Accept(",")) ts.Fail(word + " needs an auxiliary and an end position");
  }
  const KrlDecl& target = ReadKrlTarget(run, ts, &storage[0]);
  ts.Accept(",");
  if (!ts.AtEnd()) {
    const std::string option = ts.Peek().kind == TokenKind::kWord ? ts.Peek().text : ts.Rest();
    if (option != "C_DIS" && option != "C_PTP" && option != "C_VEL" && option != "C_ORI" && option != "C_SPL") {
      run.warnings.Add(word + " option " + option.substr(0, 16) + " not executed", line);
    }
  }
  Eigen::Isometry3d X_RB;
  bool in_base = false;
  SetKrlFrameAndTool(run, line, &m, &X_RB, &in_base);
  const KrlAggregate& a = target.value;
  if (target.type == "E6AXIS" || target.type == "AXIS") {
    m.has_joints = true;
    static const char* const kAxes[6] = {"A1", "A2", "A3", "A4", "A5", "A6"};
    for (int j = 0; j < 6; ++j) m.q[j] = KrlGet(a, kAxes[j], target.file, target.line, "axis position") * kPi / 180.0;
  } else {
    m.has_pose = true;
    m.frame = in_base ? TargetFrame::kRobot : TargetFrame::kUser;
    m.X_UT = X_RB * KrlPose(a, target.file, target.line);
    if (a.count("S") && a.at("S") >= 0.0 && a.at("S") <= 7.0) m.config = static_cast<int>(a.at("S"));
  }
  if (a.count("E1")) {
    m.has_positioner = true;
    m.positioner_numbered = true;
    m.tilt_rad = a.at("E1") * kPi / 180.0;
    m.rotation_rad = a.count("E2") ? a.at("E2") * kPi / 180.0 : 0.0;
  }
  if (aux != nullptr) {
    m.has_via = true;
    m.via = X_RB * KrlPose(aux->value, aux->file, aux->line).translation();
  }
  m.speed_mm_s = kind == "PTP" ? 0.0 : run.vel_mm_s;
  if (kind != "PTP" && run.vel_mm_s <= 0.0) run.warnings.Add("CP motion before any $VEL.CP: the scenario's speed used", line);
  m.weld = run.arc_on && kind != "PTP";
  run.program.motions.push_back(m);
}

// WAIT SEC t: the torch waits at its last target; WAIT FOR <condition> is warned.
void ExecKrlWait(KrlRun& run, TokenCursor& ts) {
  if (ts.Accept("SEC")) {
    if (!ts.PeekNumber()) {
      run.warnings.Add("WAIT SEC of a variable not in the timeline", ts.line());
      return;
    }
    const double s = ts.ExpectNumber("WAIT SEC");
    WAAM_THROW_UNLESS(s >= 0.0, ts.file() << ":" << ts.line() << ": WAIT SEC " << s << " must be >= 0");
    internal::AddDwell(&run.program.motions, s, ts.line(), &run.warnings);
    return;
  }
  run.warnings.Add("WAIT FOR a condition not executed", ts.line());
}

// Runs one statement of the DEF body.
void ExecKrlStatement(KrlRun& run, std::string_view text, int line) {
  TokenCursor ts(text, run.file, line);
  if (ts.Peek().kind != TokenKind::kWord) {
    run.warnings.Add("instruction " + ts.Rest().substr(0, 24) + " not executed", line);
    return;
  }
  const std::string first = ts.Next().text;
  std::string name;
  KrlDecl decl;
  if (first == "DECL" || first == "GLOBAL") {
    if (ReadKrlDecl(text, run.file, line, &name, &decl)) run.decls[name] = std::move(decl);
  } else if (first == "INI") {
  } else if (first == "BAS") {
    ExecKrlBas(run, ts);
  } else if (first == "FDAT_ACT" || first == "LDAT_ACT" || first == "PDAT_ACT") {
    ts.Expect("=", first);
    if (first == "FDAT_ACT") run.fdat = ts.ExpectWord("an FDAT name");
  } else if (first.front() == '$') {
    ExecKrlSystemAssign(run, ts, first);
  } else if ((first == "BASE_DATA" || first == "TOOL_DATA") && ts.Is("[")) {
    ExecKrlDataAssign(run, ts, first);
  } else if (first == "ARC_ON" || first == "ARC_OFF") {
    run.arc_on = first == "ARC_ON";
  } else if (first == "WAIT") {
    ExecKrlWait(run, ts);
  } else if (first == "PTP" || first == "LIN" || first == "CIRC" || first == "SPTP" || first == "SLIN" ||
             first == "SCIRC") {
    ExecKrlMotion(run, ts, first);
  } else if (first.find("WEAVE") != std::string::npos || first.compare(0, 4, "ARC_") == 0) {
    run.warnings.Add("instruction " + first.substr(0, 24) + " not executed: one bead along the path", line);
  } else {
    run.warnings.Add("instruction " + first.substr(0, 24) + " not executed", line);
  }
}

}  // namespace

ParsedProgram ReadKukaKrl(std::string_view src, std::string_view dat, const std::string& src_file,
                          const std::string& dat_file, const ProgramFrames& frames) {
  ParsedProgram program;
  program.format = ProgramFormat::kKukaKrl;
  internal::WarningList warnings;
  KrlRun run{src_file, frames, ReadKrlDat(dat, dat_file), {}, {}, program, warnings, false, 0.0, {}, {}, {}};
  const std::vector<std::string_view> lines = internal::SplitProgramLines(src, src_file);
  bool in_def = false, ended = false;
  for (std::size_t li = 0; li < lines.size() && !ended; ++li) {
    const int line = static_cast<int>(li) + 1;
    // ";" starts a comment (;FOLD / ;ENDFOLD included); "&" lines are editor attributes.
    const std::string_view l = TrimBlank(lines[li].substr(0, lines[li].find(';')));
    if (l.empty() || l.front() == '&') continue;
    const std::string u = Upper(l.substr(0, 12));
    const std::string first = u.substr(0, u.find_first_of(" \t(="));
    if (first == "DEF" || u.compare(0, 11, "GLOBAL DEF ") == 0) {
      WAAM_THROW_UNLESS(!in_def, src_file << ":" << line << ": DEF inside DEF");
      in_def = true;
      const std::string_view rest = TrimBlank(l.substr(Upper(l).find("DEF") + 3));
      program.name = std::string(TrimBlank(rest.substr(0, rest.find('('))));
      continue;
    }
    WAAM_THROW_UNLESS(in_def, src_file << ":" << line << ": expected DEF <name>( ) before '"
                                       << std::string(l.substr(0, 30)) << "'");
    if (first == "END") {
      ended = true;
      continue;
    }
    ExecKrlStatement(run, l, line);
  }
  WAAM_THROW_UNLESS(in_def, src_file << ": not a KRL program (no DEF line)");
  WAAM_THROW_UNLESS(ended, src_file << ":" << lines.size() << ": no END: the program is truncated");
  program.warnings = warnings.Take();
  return program;
}

}  // namespace waam::planner
