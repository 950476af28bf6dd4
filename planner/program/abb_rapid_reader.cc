// ABB RAPID module reader: data declarations, then the motion and arc welding instructions in file order.
#include <cctype>
#include <cmath>
#include <map>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/program/program_reader.h"

namespace waam::planner {
namespace {

using internal::ParseProgramNumber;
using internal::TrimBlank;
using internal::Upper;

// A RAPID aggregate value: a number, a word (TRUE, a name), a string or a bracketed list.
struct RapidValue {
  enum class Kind { kNumber, kWord, kString, kList } kind = Kind::kWord;
  double number = 0.0;
  std::string text;
  std::vector<RapidValue> items;
};

constexpr int kMaxRapidDepth = 8;

RapidValue ParseRapidValue(std::string_view s, std::size_t* at, int depth, const std::string& file, int line) {
  WAAM_THROW_UNLESS(depth < kMaxRapidDepth, file << ":" << line << ": RAPID value nested too deeply");
  while (*at < s.size() && std::isspace(static_cast<unsigned char>(s[*at]))) ++*at;
  WAAM_THROW_UNLESS(*at < s.size(), file << ":" << line << ": RAPID value ends early");
  RapidValue v;
  if (s[*at] == '[') {
    v.kind = RapidValue::Kind::kList;
    ++*at;
    while (true) {
      v.items.push_back(ParseRapidValue(s, at, depth + 1, file, line));
      while (*at < s.size() && std::isspace(static_cast<unsigned char>(s[*at]))) ++*at;
      WAAM_THROW_UNLESS(*at < s.size(), file << ":" << line << ": RAPID value without its closing ']'");
      if (s[*at] == ']') {
        ++*at;
        break;
      }
      WAAM_THROW_UNLESS(s[*at] == ',', file << ":" << line << ": expected ',' or ']' in a RAPID value");
      ++*at;
      WAAM_THROW_UNLESS(v.items.size() < 64, file << ":" << line << ": RAPID value with too many items");
    }
    return v;
  }
  if (s[*at] == '"') {
    v.kind = RapidValue::Kind::kString;
    const std::size_t close = s.find('"', *at + 1);
    WAAM_THROW_UNLESS(close != std::string_view::npos, file << ":" << line << ": string without its closing quote");
    v.text = std::string(s.substr(*at + 1, close - *at - 1));
    *at = close + 1;
    return v;
  }
  const std::size_t end = s.find_first_of(",]", *at);
  const std::string_view token = TrimBlank(s.substr(*at, end == std::string_view::npos ? s.size() - *at : end - *at));
  *at = end == std::string_view::npos ? s.size() : end;
  WAAM_THROW_UNLESS(!token.empty(), file << ":" << line << ": empty item in a RAPID value");
  const char c = token.front();
  if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.') {
    v.kind = RapidValue::Kind::kNumber;
    v.number = ParseProgramNumber(token, file, line, "RAPID number");
  } else {
    v.text = std::string(token);
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

struct RapidData {
  std::string type;  // lower case
  RapidValue value;
  int line = 0;
};

struct RapidStatement {
  std::string text;
  int line = 0;
};

// Top-level arguments of an instruction ("p1, v100, fine, tool0\WObj:=wobj1"), split at commas outside brackets
// and parentheses.
std::vector<std::string> SplitRapidArgs(std::string_view s) {
  std::vector<std::string> out;
  int depth = 0;
  bool quoted = false;
  std::string cur;
  for (char c : s) {
    if (c == '"') quoted = !quoted;
    if (!quoted && (c == '[' || c == '(')) ++depth;
    if (!quoted && (c == ']' || c == ')')) --depth;
    if (!quoted && depth == 0 && c == ',') {
      out.emplace_back(TrimBlank(cur));
      cur.clear();
      continue;
    }
    cur += c;
  }
  out.emplace_back(TrimBlank(cur));
  return out;
}

bool IsRapidBlockWord(const std::string& first) {
  static const char* const kWords[] = {"MODULE", "ENDMODULE", "PROC",   "ENDPROC", "FUNC",   "ENDFUNC", "TRAP",
                                       "ENDTRAP", "LOCAL",    "IF",     "ELSEIF",  "ELSE",   "ENDIF",   "FOR",
                                       "ENDFOR",  "WHILE",    "ENDWHILE", "TEST",  "CASE",   "DEFAULT:", "ENDTEST",
                                       "ERROR",   "BACKWARD", "UNDO"};
  for (const char* w : kWords) {
    if (first == w) return true;
  }
  return false;
}

}  // namespace

ParsedProgram ReadAbbRapid(std::string_view text, const std::string& file) {
  const std::vector<std::string_view> lines = internal::SplitProgramLines(text, file);
  ParsedProgram program;
  program.format = ProgramFormat::kAbbRapid;
  internal::WarningList warnings;

  // Statements: ';'-terminated, or a block line (MODULE, PROC, IF ... THEN, ENDPROC, ...) on its own.
  std::vector<RapidStatement> statements;
  std::string pending;
  int pending_line = 0;
  for (std::size_t li = 0; li < lines.size(); ++li) {
    const int line = static_cast<int>(li) + 1;
    std::string_view l = lines[li];
    bool quoted = false;
    for (std::size_t k = 0; k < l.size(); ++k) {
      if (l[k] == '"') quoted = !quoted;
      if (l[k] == '!' && !quoted) {
        l = l.substr(0, k);
        break;
      }
    }
    l = TrimBlank(l);
    if (l.empty()) continue;
    if (pending.empty()) {
      const std::string first = Upper(l.substr(0, l.find_first_of(" \t(;")));
      const bool compact_if = first == "IF" && Upper(l).find("THEN") == std::string::npos;
      if (IsRapidBlockWord(first) && !compact_if && !(first == "LOCAL" && Upper(l).find("PROC") == std::string::npos)) {
        statements.push_back({std::string(l), line});
        continue;
      }
      pending_line = line;
    }
    quoted = false;
    for (char c : l) {
      if (c == '"') quoted = !quoted;
      if (c == ';' && !quoted) {
        statements.push_back({pending, pending_line});
        pending.clear();
        pending_line = line;
        continue;
      }
      if (pending.empty() && std::isspace(static_cast<unsigned char>(c))) continue;
      pending += c;
    }
    if (!pending.empty()) pending += ' ';
    WAAM_THROW_UNLESS(pending.size() < (1u << 20), file << ":" << pending_line << ": statement longer than 1 MiB");
  }
  WAAM_THROW_UNLESS(TrimBlank(pending).empty(), file << ":" << pending_line << ": statement without its closing ';'");

  bool module_seen = false, module_closed = false;
  std::map<std::string, RapidData> data;
  bool arc_on = false;
  for (const RapidStatement& st : statements) {
    const std::string_view s = TrimBlank(st.text);
    if (s.empty()) continue;
    std::string first = Upper(s.substr(0, s.find_first_of(" \t\\(")));
    if (first == "MODULE") {
      WAAM_THROW_UNLESS(!module_seen, file << ":" << st.line << ": a second MODULE in one file");
      module_seen = true;
      std::string_view rest = TrimBlank(s.substr(6));
      program.name = std::string(rest.substr(0, rest.find_first_of(" \t(")));
      continue;
    }
    WAAM_THROW_UNLESS(module_seen, file << ":" << st.line << ": expected MODULE <name> before '"
                                        << std::string(s.substr(0, 30)) << "'");
    WAAM_THROW_UNLESS(!module_closed, file << ":" << st.line << ": text after ENDMODULE");
    if (first == "ENDMODULE") {
      module_closed = true;
      continue;
    }
    std::string_view decl = s;
    if (first == "LOCAL" || first == "TASK") {
      decl = TrimBlank(decl.substr(first.size()));
      first = Upper(decl.substr(0, decl.find_first_of(" \t")));
    }
    if (first == "PROC" || first == "ENDPROC") continue;  // procedures are run in file order
    if (first == "CONST" || first == "PERS" || first == "VAR") {
      // <CONST|PERS|VAR> <type> <name> [:= <value>]
      decl = TrimBlank(decl.substr(first.size()));
      const std::size_t type_end = decl.find_first_of(" \t");
      WAAM_THROW_UNLESS(type_end != std::string_view::npos, file << ":" << st.line << ": declaration without a name");
      const std::string type = Upper(decl.substr(0, type_end));
      decl = TrimBlank(decl.substr(type_end));
      const std::size_t assign = decl.find(":=");
      const std::string name = Upper(TrimBlank(decl.substr(0, assign)));
      WAAM_THROW_UNLESS(!name.empty(), file << ":" << st.line << ": declaration without a name");
      if (name.find('{') != std::string::npos) {
        warnings.Add("array declaration " + type + " not read", st.line);
        continue;
      }
      if (assign == std::string_view::npos) continue;  // a VAR without a value
      if (type != "ROBTARGET" && type != "JOINTTARGET" && type != "SPEEDDATA" && type != "WELDDATA" &&
          type != "WOBJDATA") {
        continue;  // tooldata (the cell's torch is used), seamdata, numbers, ...
      }
      std::size_t at = 0;
      const std::string_view value = decl.substr(assign + 2);
      RapidData d{type, ParseRapidValue(value, &at, 0, file, st.line), st.line};
      WAAM_THROW_UNLESS(TrimBlank(value.substr(at)).empty(),
                        file << ":" << st.line << ": text after the value of " << name);
      if (type == "ROBTARGET") {
        // Checked where it is declared, so a bad quaternion names this line.
        WAAM_THROW_UNLESS(d.value.kind == RapidValue::Kind::kList && d.value.items.size() == 4,
                          file << ":" << st.line << ": robtarget must be [[x,y,z],[q1..q4],[cf1,cf4,cf6,cfx],[eax]]");
        (void)RapidPose(d.value.items[0], d.value.items[1], file, st.line);
      }
      data[name] = std::move(d);
      continue;
    }
    if (IsRapidBlockWord(first)) {
      warnings.Add("RAPID " + first + " not followed (statements run in file order)", st.line);
      continue;
    }
    // Instruction: name, optional switches, arguments.
    const std::size_t name_end = s.find_first_of(" \t\\");
    std::string args_text(name_end == std::string_view::npos ? "" : s.substr(name_end));
    std::vector<std::string> args = SplitRapidArgs(args_text);
    if (args.size() == 1 && args[0].empty()) args.clear();
    while (!args.empty() && !args.front().empty() && args.front()[0] == '\\') args.erase(args.begin());
    std::string wobj;
    for (std::string& a : args) {
      // Optional arguments attached to an argument: tool0\WObj:=wobj1, weld1\Weave:=weave1.
      const std::size_t slash = a.find('\\');
      if (slash == std::string::npos) continue;
      std::string opt = Upper(a.substr(slash + 1));
      if (opt.compare(0, 6, "WOBJ:=") == 0) {
        wobj = TrimBlank(opt.substr(6));
      } else {
        warnings.Add(first + " optional argument \\" + opt.substr(0, opt.find(":=")) + " not executed", st.line);
      }
      a = std::string(TrimBlank(std::string_view(a).substr(0, slash)));
    }
    static const std::map<std::string, std::pair<MotionKind, int>> kMotions = {
        // kind, number of position arguments before the speed
        {"MOVEJ", {MotionKind::kJoint, 1}},     {"MOVEL", {MotionKind::kLinear, 1}},
        {"MOVEC", {MotionKind::kCircular, 2}},  {"MOVEABSJ", {MotionKind::kJoint, 1}},
        {"ARCLSTART", {MotionKind::kLinear, 1}}, {"ARCL", {MotionKind::kLinear, 1}},
        {"ARCLEND", {MotionKind::kLinear, 1}},  {"ARCCSTART", {MotionKind::kCircular, 2}},
        {"ARCC", {MotionKind::kCircular, 2}},   {"ARCCEND", {MotionKind::kCircular, 2}}};
    const auto motion = kMotions.find(first);
    if (motion == kMotions.end()) {
      if (first == "SETDO" && args.size() == 2) {
        const std::string signal = Upper(args[0]);
        if (signal.find("WELD") != std::string::npos || signal.find("ARC") != std::string::npos) {
          arc_on = ParseProgramNumber(args[1], file, st.line, "SetDO value") != 0.0;
          continue;
        }
      }
      if (first == "WAITTIME" && args.size() == 1) {
        // WaitTime [\InPos,] t (s): the torch waits at its last target; a time from a variable is warned.
        const std::string_view t = TrimBlank(args[0]);
        if (!t.empty() && (std::isdigit(static_cast<unsigned char>(t[0])) || t[0] == '.')) {
          internal::AddDwell(&program.motions, ParseProgramNumber(t, file, st.line, "WaitTime"), st.line, &warnings);
        } else {
          warnings.Add("WaitTime of a variable not in the timeline", st.line);
        }
        continue;
      }
      if (first == "CONFL" || first == "CONFJ" || first == "SINGAREA" || first == "ACCSET") continue;
      warnings.Add("instruction " + first.substr(0, 24) + " not executed", st.line);
      continue;
    }
    const auto [kind, n_pos] = motion->second;
    const bool arc = first.compare(0, 3, "ARC") == 0;
    const std::size_t needed = static_cast<std::size_t>(n_pos) + (arc ? 5 : 3);
    WAAM_THROW_UNLESS(args.size() == needed, file << ":" << st.line << ": " << first << " needs " << needed
                                                  << " arguments, got " << args.size());
    internal::CheckMotionCount(program.motions.size(), file, st.line);
    ProgramMotion m;
    m.kind = kind;
    m.line = st.line;
    // Targets: a declared name or a literal.
    RapidValue literals[2];
    auto value_of = [&](const std::string& arg, const char* type, RapidValue* literal) -> const RapidValue* {
      if (!arg.empty() && arg[0] == '[') {
        std::size_t at = 0;
        *literal = ParseRapidValue(arg, &at, 0, file, st.line);
        return literal;
      }
      for (char c : arg) {
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return nullptr;  // Offs(...), RelTool(...)
      }
      const auto found = data.find(Upper(arg));
      WAAM_THROW_UNLESS(found != data.end() && found->second.type == type,
                        file << ":" << st.line << ": " << arg << " is used but not declared as a " << type);
      return &found->second.value;
    };
    const bool absj = first == "MOVEABSJ";
    const RapidValue* target = value_of(args[static_cast<std::size_t>(n_pos - 1)], absj ? "JOINTTARGET" : "ROBTARGET",
                                        &literals[0]);
    const RapidValue* via = n_pos == 2 ? value_of(args[0], "ROBTARGET", &literals[1]) : nullptr;
    // Offs(p, dx, dy, dz): p moved by (dx, dy, dz) mm in its work object, a computed target the twin can follow.
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    const std::string& target_arg = args[static_cast<std::size_t>(n_pos - 1)];
    if (target == nullptr && !absj && Upper(target_arg).compare(0, 5, "OFFS(") == 0 && target_arg.back() == ')') {
      const std::vector<std::string> offs = SplitRapidArgs(std::string_view(target_arg).substr(5, target_arg.size() - 6));
      if (offs.size() == 4) {
        bool numbers = true;
        for (int k = 1; k < 4 && numbers; ++k) {
          const std::string& o = offs[static_cast<std::size_t>(k)];
          numbers = !o.empty() && o.find_first_not_of("0123456789.+-eE") == std::string::npos;
          if (numbers) offset[k - 1] = ParseProgramNumber(o, file, st.line, "Offs offset");
        }
        if (numbers) target = value_of(offs[0], "ROBTARGET", &literals[0]);
      }
    }
    if (target == nullptr || (n_pos == 2 && via == nullptr)) {
      const std::string& expr = target == nullptr ? args[static_cast<std::size_t>(n_pos - 1)] : args[0];
      warnings.Add(first + " to a computed position (" + Upper(expr.substr(0, expr.find('('))).substr(0, 16) +
                       ") not executed",
                   st.line);
      continue;
    }
    if (absj) {
      WAAM_THROW_UNLESS(target->kind == RapidValue::Kind::kList && target->items.size() == 2,
                        file << ":" << st.line << ": jointtarget must be [[j1..j6],[eax_a..eax_f]]");
      const std::vector<double> j = RapidNumbers(target->items[0], 6, file, st.line, "robax");
      m.has_joints = true;
      for (int k = 0; k < 6; ++k) m.q[k] = j[static_cast<std::size_t>(k)] * kPi / 180.0;
      const std::vector<double> e = RapidNumbers(target->items[1], 6, file, st.line, "extax");
      if (e[0] < 8e9) {  // 9E+09: an axis not in use
        m.has_positioner = true;
        m.positioner_numbered = true;
        m.tilt_rad = e[0] * kPi / 180.0;
        m.rotation_rad = e[1] < 8e9 ? e[1] * kPi / 180.0 : 0.0;
      }
    } else {
      WAAM_THROW_UNLESS(target->kind == RapidValue::Kind::kList && target->items.size() == 4,
                        file << ":" << st.line << ": robtarget must be [[x,y,z],[q1..q4],[cf1,cf4,cf6,cfx],[eax]]");
      Eigen::Isometry3d X_UT = RapidPose(target->items[0], target->items[1], file, st.line);
      X_UT.translation() += offset;
      const std::vector<double> cf = RapidNumbers(target->items[2], 4, file, st.line, "confdata");
      const int cfx = (cf[3] >= 0.0 && cf[3] <= 7.0) ? static_cast<int>(cf[3]) : -1;
      if (cfx >= 0) m.config = ((cfx & 4) ? 1 : 0) | ((cfx & 2) ? 2 : 0) | ((cfx & 1) ? 4 : 0);
      const std::vector<double> e = RapidNumbers(target->items[3], 6, file, st.line, "extax");
      if (e[0] < 8e9) {  // 9E+09: an axis not in use
        m.has_positioner = true;
        m.positioner_numbered = true;
        m.tilt_rad = e[0] * kPi / 180.0;
        m.rotation_rad = e[1] < 8e9 ? e[1] * kPi / 180.0 : 0.0;
      }
      // The work object: uframe * oframe in the robot's base frame (wobj0 = the base frame).
      Eigen::Isometry3d X_RU = Eigen::Isometry3d::Identity();
      if (!wobj.empty() && wobj != "WOBJ0") {
        const auto found = data.find(wobj);
        WAAM_THROW_UNLESS(found != data.end() && found->second.type == "WOBJDATA",
                          file << ":" << st.line << ": " << wobj << " is used but not declared as a wobjdata");
        const RapidValue& w = found->second.value;
        WAAM_THROW_UNLESS(w.kind == RapidValue::Kind::kList && w.items.size() == 5 && w.items[3].items.size() == 2 &&
                              w.items[4].items.size() == 2,
                          file << ":" << found->second.line
                               << ": wobjdata must be [robhold,ufprog,ufmec,[[x,y,z],[q]],[[x,y,z],[q]]]");
        if (Upper(w.items[0].text) == "TRUE") warnings.Add("robot-held work object (stationary tool) not modelled", st.line);
        X_RU = RapidPose(w.items[3].items[0], w.items[3].items[1], file, found->second.line) *
               RapidPose(w.items[4].items[0], w.items[4].items[1], file, found->second.line);
      }
      m.has_pose = true;
      m.frame = TargetFrame::kRobot;
      m.X_UT = X_RU * X_UT;
      if (via != nullptr) {
        WAAM_THROW_UNLESS(via->kind == RapidValue::Kind::kList && via->items.size() == 4,
                          file << ":" << st.line << ": robtarget must be [[x,y,z],[q1..q4],[cf1,cf4,cf6,cfx],[eax]]");
        const std::vector<double> v = RapidNumbers(via->items[0], 3, file, st.line, "position [x,y,z]");
        m.has_via = true;
        m.via = X_RU * Eigen::Vector3d(v[0], v[1], v[2]);
      }
    }
    // Speed: speeddata (declared, or v5 ... v7000 predefined); welded arc moves run at their welddata's weld_speed.
    const std::string speed = Upper(args[static_cast<std::size_t>(n_pos)]);
    const bool welded_move = arc && first.find("START") == std::string::npos;
    if (welded_move) {
      const auto wd = data.find(Upper(args[static_cast<std::size_t>(n_pos) + 2]));
      if (wd != data.end() && wd->second.type == "WELDDATA" && wd->second.value.kind == RapidValue::Kind::kList &&
          !wd->second.value.items.empty() && wd->second.value.items[0].kind == RapidValue::Kind::kNumber) {
        m.speed_mm_s = wd->second.value.items[0].number;
        WAAM_THROW_UNLESS(m.speed_mm_s > 0.0, file << ":" << wd->second.line << ": weld_speed must be > 0");
      } else {
        warnings.Add("welddata not declared in the module: the scenario's weld speed used", st.line);
      }
    } else {
      const auto sd = data.find(speed);
      if (sd != data.end() && sd->second.type == "SPEEDDATA") {
        m.speed_mm_s = RapidNumbers(sd->second.value, 4, file, sd->second.line, "speeddata")[0];
        WAAM_THROW_UNLESS(m.speed_mm_s > 0.0, file << ":" << sd->second.line << ": speeddata v_tcp must be > 0");
      } else if (speed.size() > 1 && speed[0] == 'V' && std::isdigit(static_cast<unsigned char>(speed[1]))) {
        m.speed_mm_s = ParseProgramNumber(speed.substr(1), file, st.line, "speed");
      } else if (speed != "VMAX") {
        warnings.Add("speeddata not declared in the module: the scenario's speed used", st.line);
      }
    }
    if (first == "ARCLSTART" || first == "ARCCSTART") {
      m.weld = false;
      arc_on = true;
    } else if (first == "ARCLEND" || first == "ARCCEND") {
      m.weld = true;
      arc_on = false;
    } else {
      m.weld = arc ? true : arc_on;
      if (arc) arc_on = true;
    }
    program.motions.push_back(m);
  }
  WAAM_THROW_UNLESS(module_seen, file << ": not a RAPID module (no MODULE line)");
  WAAM_THROW_UNLESS(module_closed, file << ":" << lines.size() << ": no ENDMODULE: the module is truncated");
  program.warnings = warnings.Take();
  return program;
}

}  // namespace waam::planner
