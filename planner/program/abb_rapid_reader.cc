// ABB RAPID module reader: statements split at ';' (block lines on their own), each tokenized; the module's data
// declarations, then PROC main run with its procedure calls, each instruction by a small function of its kind.
#include <cmath>
#include <map>
#include <optional>

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

constexpr int kMaxRapidDepth = 8;    // nesting of aggregates and expressions
constexpr int kMaxRapidCalls = 16;   // nesting of procedure calls

// A RAPID aggregate value: a number, a word (TRUE, a name), a string or a bracketed list.
struct RapidValue {
  enum class Kind { kNumber, kWord, kString, kList } kind = Kind::kWord;
  double number = 0.0;
  std::string text;
  std::vector<RapidValue> items;
};

// An argument: a literal, a data name, a function call (Offs, RelTool) or an expression the reader does not evaluate.
struct RapidExpr {
  enum class Kind { kValue, kName, kCall, kOther } kind = Kind::kOther;
  RapidValue value;
  std::string name;   // kName / kCall: upper case
  std::string text;   // as written, for messages
  std::vector<RapidExpr> args;
  std::map<std::string, std::optional<RapidExpr>> options;  // \Rx:=30, \InPos
};

struct RapidArgs {
  std::vector<RapidExpr> positional;
  std::map<std::string, std::optional<RapidExpr>> options;  // upper-case names: WOBJ, V, T, ON, WEAVE ...
};

struct RapidData {
  std::string type;  // upper case: ROBTARGET, TOOLDATA, NUM ...
  RapidValue value;
  int line = 0;
};

struct RapidStatement {
  std::string text;
  int line = 0;
};

RapidValue ReadRapidValue(TokenCursor& ts, int depth) {
  if (depth >= kMaxRapidDepth) ts.Fail("RAPID value nested too deeply");
  RapidValue v;
  if (ts.Accept("[")) {
    v.kind = RapidValue::Kind::kList;
    do {
      v.items.push_back(ReadRapidValue(ts, depth + 1));
      if (v.items.size() > 64) ts.Fail("RAPID value with too many items");
    } while (ts.Accept(","));
    ts.Expect("]", "a RAPID aggregate [a,b,...]");
  } else if (ts.PeekNumber()) {
    v.kind = RapidValue::Kind::kNumber;
    v.number = ts.ExpectNumber("RAPID number");
  } else if (ts.Peek().kind == TokenKind::kString) {
    v.kind = RapidValue::Kind::kString;
    v.text = ts.Next().text;
  } else if (ts.Peek().kind == TokenKind::kWord) {
    v.text = ts.Next().text;
  } else {
    ts.Fail("expected a RAPID value at '" + ts.Rest() + "'");
  }
  return v;
}

// The numbers of a list value of `n` numbers.
std::vector<double> RapidNumbers(const RapidValue& v, std::size_t n, const std::string& file, int line,
                                 const char* what) {
  WAAM_THROW_UNLESS(v.kind == RapidValue::Kind::kList && v.items.size() == n,
                    file << ":" << line << ": " << what << " must be a list of " << n << " numbers");
  std::vector<double> out;
  for (const RapidValue& item : v.items) {
    WAAM_THROW_UNLESS(item.kind == RapidValue::Kind::kNumber, file << ":" << line << ": " << what << " holds '"
                                                                  << item.text.substr(0, 20) << "', not a number");
    out.push_back(item.number);
  }
  return out;
}

// [[x,y,z],[q1,q2,q3,q4]] -> pose (q1 the scalar part; a quaternion must be of unit length).
Eigen::Isometry3d RapidPose(const RapidValue& pos, const RapidValue& rot, const std::string& file, int line) {
  const std::vector<double> p = RapidNumbers(pos, 3, file, line, "position [x,y,z]");
  const std::vector<double> q = RapidNumbers(rot, 4, file, line, "orientation [q1,q2,q3,q4]");
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  WAAM_THROW_UNLESS(norm > 1e-9, file << ":" << line << ": quaternion [0,0,0,0] of length 0");
  WAAM_THROW_UNLESS(std::abs(norm - 1.0) < 1e-2,
                    file << ":" << line << ": quaternion of length " << norm << ": must be normalised (length 1)");
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  X.linear() = Eigen::Quaterniond(q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm).toRotationMatrix();
  return X;
}

// Checks an aggregate of `items` items whose `pose` item is a pose [[x,y,z],[q]]: robtarget (pose 0, four items),
// tooldata (pose 1 of three), wobjdata (poses 3 and 4 of five).
void CheckRapidShape(const RapidValue& v, std::size_t items, std::initializer_list<std::size_t> poses,
                     const std::string& file, int line, const char* form) {
  WAAM_THROW_UNLESS(v.kind == RapidValue::Kind::kList && v.items.size() == items, file << ":" << line << ": " << form);
  for (std::size_t k : poses) {
    const RapidValue& p = v.items[k];
    WAAM_THROW_UNLESS(p.kind == RapidValue::Kind::kList && p.items.size() == 2, file << ":" << line << ": " << form);
    (void)RapidPose(p.items[0], p.items[1], file, line);
  }
}

constexpr const char* kRobtargetForm = "robtarget must be [[x,y,z],[q1..q4],[cf1,cf4,cf6,cfx],[eax]]";
constexpr const char* kTooldataForm = "tooldata must be [robhold,[[x,y,z],[q1..q4]],[mass,[cog],[aom],ix,iy,iz]]";
constexpr const char* kWobjdataForm = "wobjdata must be [robhold,ufprog,ufmec,[[x,y,z],[q]],[[x,y,z],[q]]]";

std::optional<RapidExpr> ReadRapidOption(TokenCursor& ts, int depth, std::string* name);

// One argument or operand: a literal aggregate or number, a name, a call Name(args), or an expression (kOther).
RapidExpr ReadRapidExpr(TokenCursor& ts, int depth) {
  if (depth >= kMaxRapidDepth) ts.Fail("RAPID expression nested too deeply");
  RapidExpr e;
  e.text = ts.Peek().raw.substr(0, 24);
  if (ts.Is("[") || ts.PeekNumber() || ts.Peek().kind == TokenKind::kString) {
    e.kind = RapidExpr::Kind::kValue;
    e.value = ReadRapidValue(ts, depth);
  } else if (ts.Peek().kind == TokenKind::kWord && ts.Is("(", 1)) {
    e.kind = RapidExpr::Kind::kCall;
    e.name = ts.Next().text;
    ts.Next();
    while (!ts.Accept(")")) {
      if (ts.AtEnd()) ts.Fail(e.name + "( without its ')'");
      std::string option;
      if (ts.Is("\\")) {
        std::optional<RapidExpr> v = ReadRapidOption(ts, depth + 1, &option);
        e.options[option] = std::move(v);
      } else if (!ts.Accept(",")) {
        e.args.push_back(ReadRapidExpr(ts, depth + 1));
      }
    }
  } else if (ts.Peek().kind == TokenKind::kWord) {
    e.kind = RapidExpr::Kind::kName;
    e.name = ts.Next().text;
  }
  // An operator or anything else after the operand: an expression the reader does not evaluate.
  if (e.kind == RapidExpr::Kind::kOther || !(ts.AtEnd() || ts.Is(",") || ts.Is(")") || ts.Is("\\"))) {
    e.kind = RapidExpr::Kind::kOther;
    int nesting = 0;
    while (!ts.AtEnd() && !(nesting == 0 && (ts.Is(",") || ts.Is(")") || ts.Is("\\")))) {
      const std::string t = ts.Next().text;
      nesting += (t == "(" || t == "[") ? 1 : ((t == ")" || t == "]") ? -1 : 0);
    }
  }
  return e;
}

// "\Name" or "\Name:=value" at the cursor.
std::optional<RapidExpr> ReadRapidOption(TokenCursor& ts, int depth, std::string* name) {
  ts.Expect("\\", "an optional argument");
  *name = ts.ExpectWord("an optional argument's name");
  if (!ts.Accept(":")) return std::nullopt;
  ts.Expect("=", "an optional argument \\" + *name + ":=");
  return ReadRapidExpr(ts, depth);
}

// An instruction's arguments: "p1, v100, fine, tool0\WObj:=wobj1" or "\InPos, 1".
RapidArgs ReadRapidArgs(TokenCursor& ts) {
  RapidArgs args;
  while (!ts.AtEnd()) {
    if (ts.Accept(",")) continue;
    if (ts.Is("\\")) {
      std::string name;
      std::optional<RapidExpr> v = ReadRapidOption(ts, 0, &name);
      args.options[name] = std::move(v);
      continue;
    }
    args.positional.push_back(ReadRapidExpr(ts, 0));
    if (args.positional.size() > 32) ts.Fail("instruction with too many arguments");
  }
  return args;
}

bool IsRapidBlockWord(const std::string& first) {
  static const char* const kWords[] = {"MODULE", "ENDMODULE", "PROC",   "ENDPROC",  "FUNC",     "ENDFUNC", "TRAP",
                                       "ENDTRAP", "LOCAL",    "IF",     "ELSEIF",   "ELSE",     "ENDIF",   "FOR",
                                       "ENDFOR",  "WHILE",    "ENDWHILE", "TEST",   "CASE",     "DEFAULT", "ENDTEST",
                                       "ERROR",   "BACKWARD", "UNDO",   "TASK"};
  for (const char* w : kWords) {
    if (first == w) return true;
  }
  return false;
}

// Statements: ';'-terminated (over several lines: multi-line aggregates), or a block line (MODULE, PROC, IF ... THEN,
// ENDPROC ...) on its own; '!' starts a comment outside strings.
std::vector<RapidStatement> SplitRapidStatements(const std::vector<std::string_view>& lines, const std::string& file) {
  std::vector<RapidStatement> statements;
  std::string pending;
  int pending_line = 0;
  bool header = false;  // between the "%%%" lines of an S4 .prg header (VERSION, LANGUAGE)
  for (std::size_t li = 0; li < lines.size(); ++li) {
    const int line = static_cast<int>(li) + 1;
    std::string_view l = lines[li];
    if (TrimBlank(l) == "%%%") header = !header;
    if (header || TrimBlank(l) == "%%%") continue;
    bool quoted = false;
    for (std::size_t k = 0; k < l.size(); ++k) {
      if (l[k] == '"') quoted = !quoted;
      if (l[k] == '!' && !quoted) l = l.substr(0, k);
    }
    l = TrimBlank(l);
    if (l.empty()) continue;
    if (pending.empty()) {
      const std::string u = Upper(l);
      const std::string first = u.substr(0, u.find_first_of(" \t(;:"));
      const bool declaration = (first == "LOCAL" || first == "TASK") && u.find("PROC") == std::string::npos &&
                               u.find("FUNC") == std::string::npos && u.find("TRAP") == std::string::npos;
      const bool compact_if = first == "IF" && u.find("THEN") == std::string::npos;
      if (IsRapidBlockWord(first) && !compact_if && !declaration && u.back() != ';') {
        statements.push_back({std::string(l), line});
        continue;
      }
      pending_line = line;
    }
    quoted = false;
    for (char c : l) {
      if (c == '"') quoted = !quoted;
      if (c == ';' && !quoted) {
        if (!TrimBlank(pending).empty()) statements.push_back({pending, pending_line});
        pending.clear();
        pending_line = line;
        continue;
      }
      pending += c;
    }
    if (!TrimBlank(pending).empty()) pending += ' ';
    WAAM_THROW_UNLESS(pending.size() < (1u << 20), file << ":" << pending_line << ": statement longer than 1 MiB");
  }
  WAAM_THROW_UNLESS(TrimBlank(pending).empty(), file << ":" << pending_line << ": statement without its closing ';'");
  return statements;
}

// The module: its data (declared at module level and, as they run, inside procedures) and its procedures.
struct RapidModule {
  std::string name;
  std::map<std::string, RapidData> data;
  std::map<std::string, std::pair<std::size_t, std::size_t>> procs;  // statements [first, last) of each PROC body
  std::vector<RapidStatement> statements;
  std::string first_proc;
};

// "[LOCAL|TASK] CONST|PERS|VAR <type> <name> [:= <value>]": the data, checked where it is declared; false for an
// array or a declaration without a value.
bool ReadRapidDecl(TokenCursor& ts, const std::string& file, internal::WarningList* warnings, std::string* name,
                   RapidData* data) {
  while (ts.Accept("LOCAL") || ts.Accept("TASK")) {
  }
  ts.Next();  // CONST, PERS or VAR
  data->type = ts.ExpectWord("a data type");
  *name = ts.ExpectWord("a data name");
  data->line = ts.line();
  if (ts.Is("{")) {
    warnings->Add("array declaration " + data->type + " not read", ts.line());
    return false;
  }
  if (!ts.Accept(":")) return false;
  ts.Expect("=", "declaration of " + *name);
  data->value = ReadRapidValue(ts, 0);
  if (!ts.AtEnd()) ts.Fail("text after the value of " + *name + ": '" + ts.Rest() + "'");
  if (data->type == "ROBTARGET") {
    CheckRapidShape(data->value, 4, {}, file, ts.line(), kRobtargetForm);
    (void)RapidPose(data->value.items[0], data->value.items[1], file, ts.line());
  }
  if (data->type == "TOOLDATA") CheckRapidShape(data->value, 3, {1}, file, ts.line(), kTooldataForm);
  if (data->type == "WOBJDATA") CheckRapidShape(data->value, 5, {3, 4}, file, ts.line(), kWobjdataForm);
  return true;
}

bool IsRapidDeclaration(TokenCursor& ts) {
  std::size_t k = 0;
  while (ts.Is("LOCAL", k) || ts.Is("TASK", k)) ++k;
  return ts.Is("CONST", k) || ts.Is("PERS", k) || ts.Is("VAR", k);
}

// MODULE name ... ENDMODULE: the module-level data and where each PROC's body lies.
RapidModule ReadRapidModule(std::vector<RapidStatement> statements, const std::string& file, int last_line,
                            internal::WarningList* warnings) {
  RapidModule module;
  module.statements = std::move(statements);
  bool closed = false;
  std::string proc;
  for (std::size_t i = 0; i < module.statements.size(); ++i) {
    const RapidStatement& st = module.statements[i];
    TokenCursor ts(st.text, file, st.line);
    if (module.name.empty()) {
      if (!ts.Accept("MODULE")) ts.Fail("expected MODULE <name> before '" + st.text.substr(0, 30) + "'");
      module.name = ts.Peek().raw;
      continue;
    }
    if (closed) ts.Fail("text after ENDMODULE");
    if (ts.Is("MODULE")) ts.Fail("a second MODULE in one file");
    ts.Accept("LOCAL");
    if (ts.Accept("PROC")) {
      proc = ts.ExpectWord("a procedure name");
      if (module.first_proc.empty()) module.first_proc = proc;
      module.procs[proc] = {i + 1, i + 1};
    } else if (ts.Accept("ENDPROC")) {
      if (!proc.empty()) module.procs[proc].second = i;
      proc.clear();
    } else if (ts.Accept("ENDMODULE")) {
      closed = true;
    } else if (proc.empty() && IsRapidDeclaration(ts)) {
      std::string name;
      RapidData data;
      if (ReadRapidDecl(ts, file, warnings, &name, &data)) module.data[name] = std::move(data);
    }
  }
  WAAM_THROW_UNLESS(!module.name.empty(), file << ": not a RAPID module (no MODULE line)");
  WAAM_THROW_UNLESS(closed, file << ":" << last_line << ": no ENDMODULE: the module is truncated");
  return module;
}

// What runs while PROC main executes.
struct RapidRun {
  const std::string& file;
  RapidModule& module;
  ParsedProgram& program;
  internal::WarningList& warnings;
  bool arc_on = false;
  double velset_override = 1.0;  // VelSet Override (fraction)
  double velset_max = 0.0;       // VelSet Max (mm/s; 0: none)
};

const RapidData* FindRapidData(const RapidRun& run, const std::string& name, const char* type) {
  const auto found = run.module.data.find(name);
  return found != run.module.data.end() && found->second.type == type ? &found->second : nullptr;
}

// A number argument: a literal, a negated literal or a declared num; empty when computed.
std::optional<double> RapidNumber(const RapidRun& run, const RapidExpr& e) {
  if (e.kind == RapidExpr::Kind::kValue && e.value.kind == RapidValue::Kind::kNumber) return e.value.number;
  if (e.kind == RapidExpr::Kind::kName) {
    const RapidData* d = FindRapidData(run, e.name, "NUM");
    if (d == nullptr) d = FindRapidData(run, e.name, "DNUM");
    if (d != nullptr && d->value.kind == RapidValue::Kind::kNumber) return d->value.number;
  }
  return std::nullopt;
}

// A robtarget argument: a declared name, a literal, Offs(p, dx, dy, dz) (mm in the work object) or
// RelTool(p, dx, dy, dz [\Rx] [\Ry] [\Rz]) (mm and deg in the tool frame: about x, then y, then z); empty when
// computed otherwise. `value` receives the robtarget's aggregate (configuration and external axes).
std::optional<Eigen::Isometry3d> RapidTarget(const RapidRun& run, const RapidExpr& e, int line, RapidValue* value) {
  if (e.kind == RapidExpr::Kind::kValue || e.kind == RapidExpr::Kind::kName) {
    if (e.kind == RapidExpr::Kind::kName) {
      const RapidData* d = FindRapidData(run, e.name, "ROBTARGET");
      WAAM_THROW_UNLESS(d != nullptr, run.file << ":" << line << ": " << e.text
                                               << " is used but not declared as a ROBTARGET");
      *value = d->value;
    } else {
      *value = e.value;
    }
    CheckRapidShape(*value, 4, {}, run.file, line, kRobtargetForm);
    return RapidPose(value->items[0], value->items[1], run.file, line);
  }
  const bool offs = e.name == "OFFS", reltool = e.name == "RELTOOL";
  if (e.kind != RapidExpr::Kind::kCall || (!offs && !reltool) || e.args.size() != 4) return std::nullopt;
  std::optional<Eigen::Isometry3d> X = RapidTarget(run, e.args[0], line, value);
  Eigen::Vector3d d;
  for (int k = 0; k < 3; ++k) {
    const std::optional<double> v = RapidNumber(run, e.args[static_cast<std::size_t>(k) + 1]);
    if (!v || !X) return std::nullopt;
    d[k] = *v;
  }
  if (offs) {
    X->translation() += d;
    return X;
  }
  X->translate(d);
  for (const char* axis : {"RX", "RY", "RZ"}) {
    const auto o = e.options.find(axis);
    if (o == e.options.end()) continue;
    const std::optional<double> deg = o->second ? RapidNumber(run, *o->second) : std::nullopt;
    if (!deg) return std::nullopt;
    const Eigen::Vector3d about = axis[1] == 'X' ? Eigen::Vector3d::UnitX()
                                                 : (axis[1] == 'Y' ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ());
    X->rotate(Eigen::AngleAxisd(*deg / kDeg, about));
  }
  return X;
}

// External axes eax_a, eax_b (deg; 9E+09: not in use) as the numbered positioner axes.
void SetRapidExternalAxes(const RapidValue& eax, const std::string& file, int line, ProgramMotion* m) {
  const std::vector<double> e = RapidNumbers(eax, 6, file, line, "extax");
  if (e[0] >= 8e9) return;
  m->has_positioner = true;
  m->positioner_numbered = true;
  m->tilt_rad = e[0] / kDeg;
  m->rotation_rad = e[1] < 8e9 ? e[1] / kDeg : 0.0;
}

// The work object of \WObj (wobj0 or none: the robot's base frame): uframe * oframe.
Eigen::Isometry3d RapidWorkObject(RapidRun& run, const RapidArgs& args, int line) {
  const auto w = args.options.find("WOBJ");
  if (w == args.options.end() || !w->second || w->second->name == "WOBJ0") return Eigen::Isometry3d::Identity();
  const RapidData* d = FindRapidData(run, w->second->name, "WOBJDATA");
  WAAM_THROW_UNLESS(d != nullptr, run.file << ":" << line << ": " << w->second->text
                                           << " is used but not declared as a wobjdata");
  const RapidValue& v = d->value;
  if (v.items[0].text == "TRUE") run.warnings.Add("robot-held work object (stationary tool) not modelled", line);
  if (v.items[1].text == "FALSE") {
    run.warnings.Add("work object moved by a mechanical unit (" + v.items[2].text.substr(0, 16) +
                         "): positions taken with the unit at zero",
                     line);
  }
  return RapidPose(v.items[3].items[0], v.items[3].items[1], run.file, d->line) *
         RapidPose(v.items[4].items[0], v.items[4].items[1], run.file, d->line);
}

// ABB's flange frame Fabb in the twin's flange frame F (X_F_Fabb): ABB's z along the flange normal, x down at the zero
// pose; the twin's x along the normal (x_abb = -z_F, y_abb = y_F, z_abb = x_F).
Eigen::Isometry3d AbbFlangeInTwinFlange() {
  Eigen::Isometry3d X_F_Fabb = Eigen::Isometry3d::Identity();
  X_F_Fabb.linear() << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  return X_F_Fabb;
}

// The tool argument: a tooldata the module declares (its tframe in ABB's flange frame), tool0 (the flange), or one
// kept on the controller (the cell's torch, warned).
void SetRapidTool(RapidRun& run, const RapidExpr& tool, int line, ProgramMotion* m) {
  if (tool.kind != RapidExpr::Kind::kName) {
    run.warnings.Add("tool from an expression: the cell's torch", line);
    return;
  }
  m->tool_name = tool.text;
  if (tool.name == "TOOL0") {
    m->has_tool = true;
    m->X_FT = AbbFlangeInTwinFlange();
    return;
  }
  const RapidData* d = FindRapidData(run, tool.name, "TOOLDATA");
  if (d == nullptr) {
    run.warnings.Add("tooldata " + tool.text + " not declared in the module: the cell's torch", line);
    return;
  }
  if (d->value.items[0].text == "FALSE") {
    run.warnings.Add("stationary tool " + tool.text + " (robhold FALSE) not modelled: the cell's torch", line);
    return;
  }
  m->has_tool = true;
  m->X_FT = AbbFlangeInTwinFlange() * RapidPose(d->value.items[1].items[0], d->value.items[1].items[1], run.file, d->line);
}

// The TCP speed of a move (mm/s; 0: the scenario's): welded Arc moves at their welddata's weld_speed, others at their
// speeddata (declared, a literal, or the predefined v5 ... v7000; vmax the scenario's), \V:= in its stead; VelSet's
// override and maximum applied.
double RapidSpeed(RapidRun& run, const RapidArgs& args, std::size_t speed_at, bool welded, int line) {
  double v = 0.0;
  const RapidExpr& speed = args.positional[speed_at];
  const RapidData* wd = welded ? FindRapidData(run, args.positional[speed_at + 2].name, "WELDDATA") : nullptr;
  const RapidData* sd = FindRapidData(run, speed.name, "SPEEDDATA");
  const RapidValue* value = sd != nullptr ? &sd->value : (speed.kind == RapidExpr::Kind::kValue ? &speed.value : nullptr);
  if (welded) {
    if (wd != nullptr && wd->value.kind == RapidValue::Kind::kList && !wd->value.items.empty() &&
        wd->value.items[0].kind == RapidValue::Kind::kNumber) {
      v = wd->value.items[0].number;
      WAAM_THROW_UNLESS(v > 0.0, run.file << ":" << wd->line << ": weld_speed must be > 0");
    } else {
      run.warnings.Add("welddata not declared in the module: the scenario's weld speed used", line);
    }
  } else if (value != nullptr) {
    v = RapidNumbers(*value, 4, run.file, sd != nullptr ? sd->line : line, "speeddata")[0];
    WAAM_THROW_UNLESS(v > 0.0, run.file << ":" << (sd != nullptr ? sd->line : line) << ": speeddata v_tcp must be > 0");
  } else if (speed.kind == RapidExpr::Kind::kName && speed.name.size() > 1 && speed.name[0] == 'V' &&
             speed.name.find_first_not_of("0123456789.", 1) == std::string::npos) {
    v = internal::ParseProgramNumber(speed.name.substr(1), run.file, line, "speed");
  } else if (speed.name != "VMAX") {
    run.warnings.Add("speeddata not declared in the module: the scenario's speed used", line);
  }
  const auto vv = args.options.find("V");
  if (!welded && vv != args.options.end() && vv->second) v = RapidNumber(run, *vv->second).value_or(v);
  if (args.options.count("T")) run.warnings.Add("\\T move time not followed: the move's speed used", line);
  if (v > 0.0) v *= run.velset_override;
  if (v > 0.0 && run.velset_max > 0.0) v = std::min(v, run.velset_max);
  return v;
}

// The motion instructions: kind, positions before the speed, whether the arc instructions' seam and weld follow.
struct RapidMotionForm {
  MotionKind kind;
  int positions;
  bool arc;
};

std::optional<RapidMotionForm> RapidMotionOf(const std::string& name) {
  static const std::map<std::string, RapidMotionForm> kForms = {
      {"MOVEJ", {MotionKind::kJoint, 1, false}},     {"MOVEL", {MotionKind::kLinear, 1, false}},
      {"MOVEC", {MotionKind::kCircular, 2, false}},  {"MOVEABSJ", {MotionKind::kJoint, 1, false}},
      {"TRIGGJ", {MotionKind::kJoint, 1, false}},    {"TRIGGL", {MotionKind::kLinear, 1, false}},
      {"TRIGGC", {MotionKind::kCircular, 2, false}}, {"ARCLSTART", {MotionKind::kLinear, 1, true}},
      {"ARCL", {MotionKind::kLinear, 1, true}},      {"ARCLEND", {MotionKind::kLinear, 1, true}},
      {"ARCCSTART", {MotionKind::kCircular, 2, true}}, {"ARCC", {MotionKind::kCircular, 2, true}},
      {"ARCCEND", {MotionKind::kCircular, 2, true}}};
  const auto found = kForms.find(name);
  return found == kForms.end() ? std::nullopt : std::optional<RapidMotionForm>(found->second);
}

// Warns the optional arguments a motion does not execute (\WObj, \V, \T, \On, \Off are taken; zones, IDs and the
// like change nothing on the path).
void WarnRapidMotionOptions(RapidRun& run, const std::string& name, const RapidArgs& args, int line) {
  static const char* const kQuiet[] = {"WOBJ", "V", "T", "ON", "OFF", "Z", "INPOS", "ID", "CONC", "TLOAD",
                                       "NOEOFFS", "SEAMNAME", "CORR", "T2", "T3", "T4"};
  for (const auto& [option, value] : args.options) {
    bool quiet = false;
    for (const char* q : kQuiet) quiet = quiet || option == q;
    if (!quiet) run.warnings.Add(name + " optional argument \\" + option + " not executed", line);
  }
}

// MoveJ / MoveL / MoveC / MoveAbsJ / TriggX / ArcX: targets, speed, tool and work object, the arc switching.
void ExecRapidMotion(RapidRun& run, const std::string& name, const RapidMotionForm& form, const RapidArgs& args,
                     int line) {
  const std::size_t speed_at = static_cast<std::size_t>(form.positions);
  const std::size_t needed = speed_at + (form.arc ? 5 : (name.compare(0, 5, "TRIGG") == 0 ? 4 : 3));
  WAAM_THROW_UNLESS(args.positional.size() >= needed, run.file << ":" << line << ": " << name << " needs " << needed
                                                              << " arguments, got " << args.positional.size());
  internal::CheckMotionCount(run.program.motions.size(), run.file, line);
  WarnRapidMotionOptions(run, name, args, line);
  ProgramMotion m;
  m.kind = form.kind;
  m.line = line;
  const RapidExpr& target = args.positional[speed_at - 1];
  if (name == "MOVEABSJ") {
    const RapidData* d = FindRapidData(run, target.name, "JOINTTARGET");
    const RapidValue* v = target.kind == RapidExpr::Kind::kValue ? &target.value : (d ? &d->value : nullptr);
    WAAM_THROW_UNLESS(v != nullptr, run.file << ":" << line << ": " << target.text
                                             << " is used but not declared as a JOINTTARGET");
    WAAM_THROW_UNLESS(v->kind == RapidValue::Kind::kList && v->items.size() == 2,
                      run.file << ":" << line << ": jointtarget must be [[j1..j6],[eax_a..eax_f]]");
    const std::vector<double> j = RapidNumbers(v->items[0], 6, run.file, line, "robax");
    m.has_joints = true;
    for (int k = 0; k < 6; ++k) m.q[k] = j[static_cast<std::size_t>(k)] / kDeg;
    SetRapidExternalAxes(v->items[1], run.file, line, &m);
  } else {
    RapidValue value, via_value;
    const std::optional<Eigen::Isometry3d> X = RapidTarget(run, target, line, &value);
    const std::optional<Eigen::Isometry3d> via =
        form.positions == 2 ? RapidTarget(run, args.positional[0], line, &via_value) : std::nullopt;
    if (!X || (form.positions == 2 && !via)) {
      const RapidExpr& e = !X ? target : args.positional[0];
      run.warnings.Add(name + " to a computed position (" + Upper(e.text.substr(0, e.text.find('('))).substr(0, 16) +
                           ") not executed",
                       line);
      return;
    }
    const Eigen::Isometry3d X_RU = RapidWorkObject(run, args, line);
    m.has_pose = true;
    m.frame = TargetFrame::kRobot;
    m.X_UT = X_RU * *X;
    if (via) m.has_via = true, m.via = X_RU * via->translation();
    const std::vector<double> cf = RapidNumbers(value.items[2], 4, run.file, line, "confdata");
    const int cfx = (cf[3] >= 0.0 && cf[3] <= 7.0) ? static_cast<int>(cf[3]) : -1;
    if (cfx >= 0) m.config = ((cfx & 4) ? 1 : 0) | ((cfx & 2) ? 2 : 0) | ((cfx & 1) ? 4 : 0);
    SetRapidExternalAxes(value.items[3], run.file, line, &m);
  }
  SetRapidTool(run, args.positional[needed - 1], line, &m);
  const bool start = name.find("START") != std::string::npos || args.options.count("ON");
  const bool end = name.find("END") != std::string::npos || args.options.count("OFF");
  m.speed_mm_s = RapidSpeed(run, args, speed_at, form.arc && !start, line);
  // ArcXStart moves to the seam and strikes the arc there; ArcX welds; ArcXEnd welds and ends the arc.
  m.weld = form.arc ? !start : run.arc_on;
  if (form.arc) run.arc_on = !end;
  run.program.motions.push_back(m);
}

void RunRapidProc(RapidRun& run, const std::string& name, int depth, int line);

// One statement of a procedure body.
void ExecRapidStatement(RapidRun& run, const RapidStatement& st, int depth) {
  TokenCursor ts(st.text, run.file, st.line);
  if (IsRapidDeclaration(ts)) {
    std::string name;
    RapidData data;
    if (ReadRapidDecl(ts, run.file, &run.warnings, &name, &data)) run.module.data[name] = std::move(data);
    return;
  }
  const std::string first = ts.ExpectWord("an instruction");
  if (IsRapidBlockWord(first)) {
    // IF / FOR / WHILE / TEST are not evaluated; their END lines close nothing the reader opened.
    if (first.compare(0, 3, "END") != 0) {
      run.warnings.Add("RAPID " + first + " not followed (its statements run in order)", st.line);
    }
    return;
  }
  if (ts.Is(":") && ts.Is("=", 1)) {
    run.warnings.Add("assignment to " + first.substr(0, 24) + " not executed", st.line);
    return;
  }
  const RapidArgs args = ReadRapidArgs(ts);
  if (const std::optional<RapidMotionForm> form = RapidMotionOf(first)) {
    ExecRapidMotion(run, first, *form, args, st.line);
  } else if (run.module.procs.count(first)) {
    RunRapidProc(run, first, depth + 1, st.line);
  } else if (first == "WAITTIME") {
    // WaitTime [\InPos,] t (s): the torch waits at its last target; a time the reader cannot evaluate is warned.
    const std::optional<double> t = args.positional.size() == 1 ? RapidNumber(run, args.positional[0]) : std::nullopt;
    if (!t) {
      run.warnings.Add("WaitTime of a variable not in the timeline", st.line);
      return;
    }
    WAAM_THROW_UNLESS(*t >= 0.0, run.file << ":" << st.line << ": WaitTime " << *t << " must be >= 0");
    internal::AddDwell(&run.program.motions, *t, st.line, &run.warnings);
  } else if ((first == "SETDO" || first == "SET" || first == "RESET") && !args.positional.empty() &&
             (args.positional[0].name.find("WELD") != std::string::npos ||
              args.positional[0].name.find("ARC") != std::string::npos)) {
    // A digital output named for the weld or the arc switches it: SetDO sig, 1 / Set sig / Reset sig.
    const std::optional<double> v = first == "SETDO" && args.positional.size() == 2
                                        ? RapidNumber(run, args.positional[1])
                                        : std::optional<double>(first == "SET" ? 1.0 : 0.0);
    if (!v) ts.Fail("SetDO " + args.positional[0].text + " needs its value 0 or 1");
    run.arc_on = *v != 0.0;
  } else if (first == "VELSET" && args.positional.size() == 2) {
    const std::optional<double> o = RapidNumber(run, args.positional[0]), mx = RapidNumber(run, args.positional[1]);
    if (!o || !mx || *o <= 0.0 || *mx <= 0.0) ts.Fail("VelSet needs an override (%) and a maximum (mm/s) > 0");
    run.velset_override = *o / 100.0, run.velset_max = *mx;
  } else if (first != "CONFL" && first != "CONFJ" && first != "SINGAREA" && first != "TPWRITE" && first != "TPERASE") {
    run.warnings.Add("instruction " + first.substr(0, 24) + " not executed", st.line);
  }
}

// Runs a PROC of the module (main, or one it calls).
void RunRapidProc(RapidRun& run, const std::string& name, int depth, int line) {
  WAAM_THROW_UNLESS(depth < kMaxRapidCalls, run.file << ":" << line << ": procedure calls nested deeper than "
                                                     << kMaxRapidCalls << " (" << name << " calls itself?)");
  const auto [first, last] = run.module.procs.at(name);
  for (std::size_t i = first; i < last; ++i) ExecRapidStatement(run, run.module.statements[i], depth);
}

}  // namespace

ParsedProgram ReadAbbRapid(std::string_view text, const std::string& file) {
  const std::vector<std::string_view> lines = internal::SplitProgramLines(text, file);
  ParsedProgram program;
  program.format = ProgramFormat::kAbbRapid;
  internal::WarningList warnings;
  RapidModule module =
      ReadRapidModule(SplitRapidStatements(lines, file), file, static_cast<int>(lines.size()), &warnings);
  program.name = module.name;
  RapidRun run{file, module, program, warnings, false, 1.0, 0.0};
  const std::string entry = module.procs.count("MAIN") ? "MAIN" : module.first_proc;
  if (entry.empty()) {
    warnings.Add("module without a procedure: nothing runs", 1);
  } else {
    if (entry != "MAIN") warnings.Add("no PROC main: " + entry + " run as the entry", 1);
    RunRapidProc(run, entry, 0, 1);
  }
  program.warnings = warnings.Take();
  return program;
}

}  // namespace waam::planner
