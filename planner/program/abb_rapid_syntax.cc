// ABB RAPID's syntax for the reader: values, arguments and expressions, statements, declarations, the module.
#include "planner/program/abb_rapid_syntax.h"

#include <cmath>

#include "models/core/error.h"

namespace waam::planner::internal {
namespace {

constexpr int kMaxRapidDepth = 8;  // nesting of aggregates and expressions

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

}  // namespace

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


namespace {

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

}  // namespace

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


// "[LOCAL|TASK] CONST|PERS|VAR <type> <name> [:= <value>]": the data, checked where it is declared; false for an
// array or a declaration without a value.
bool ReadRapidDecl(TokenCursor& ts, const std::string& file, WarningList* warnings, std::string* name,
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
                            WarningList* warnings) {
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

}  // namespace waam::planner::internal
