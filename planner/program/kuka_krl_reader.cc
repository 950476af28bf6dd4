// KUKA KRL reader: the .dat declarations (E6POS, POS, E6AXIS, AXIS), then the .src motions (PTP, LIN, CIRC), speeds
// ($VEL.CP, BAS(#CP_PARAMS)), $BASE frames and arc switching ($OUT, ArcTech ARC_ON / ARC_OFF).
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

using KrlAggregate = std::map<std::string, double>;

struct KrlDecl {
  std::string type;  // E6POS, POS, E6AXIS, AXIS, FRAME
  KrlAggregate value;
  int line = 0;
  std::string file;
};

// "{X 1.0,Y 2,A 90,...}" -> {"X": 1, ...}.
KrlAggregate ParseKrlAggregate(std::string_view text, const std::string& file, int line) {
  text = TrimBlank(text);
  WAAM_THROW_UNLESS(text.size() >= 2 && text.front() == '{' && text.back() == '}',
                    file << ":" << line << ": expected a KRL aggregate {X 1.0,Y 2.0,...}");
  KrlAggregate out;
  std::string_view body = text.substr(1, text.size() - 2);
  while (!body.empty()) {
    const std::size_t comma = body.find(',');
    std::string_view item = TrimBlank(body.substr(0, comma));
    body = comma == std::string_view::npos ? std::string_view() : body.substr(comma + 1);
    if (item.empty()) continue;
    const std::size_t space = item.find_first_of(" \t");
    WAAM_THROW_UNLESS(space != std::string_view::npos,
                      file << ":" << line << ": aggregate item '" << std::string(item.substr(0, 20)) << "' has no value");
    const std::string key = Upper(item.substr(0, space));
    WAAM_THROW_UNLESS(key.find_first_of("{}") == std::string::npos,
                      file << ":" << line << ": nested aggregates are not positions");
    out[key] = ParseProgramNumber(item.substr(space + 1), file, line, key);
    WAAM_THROW_UNLESS(out.size() < 64, file << ":" << line << ": aggregate with too many items");
  }
  return out;
}

// "DECL E6POS XP1={...}" (DECL may be missing in a .dat) -> name, declaration; false for other declarations.
bool ParseKrlDecl(std::string_view line_text, const std::string& file, int line, std::string* name, KrlDecl* decl) {
  std::string_view t = TrimBlank(line_text);
  std::string u = Upper(t);
  if (u.compare(0, 7, "GLOBAL ") == 0) t = TrimBlank(t.substr(7)), u = Upper(t);
  if (u.compare(0, 5, "DECL ") == 0) t = TrimBlank(t.substr(5)), u = Upper(t);
  const std::size_t space = u.find_first_of(" \t");
  if (space == std::string::npos) return false;
  const std::string type = u.substr(0, space);
  if (type != "E6POS" && type != "POS" && type != "E6AXIS" && type != "AXIS" && type != "FRAME") return false;
  const std::size_t eq = t.find('=');
  if (eq == std::string_view::npos) return false;  // declared without a value
  *name = Upper(TrimBlank(t.substr(space, eq - space)));
  decl->type = type;
  decl->value = ParseKrlAggregate(t.substr(eq + 1), file, line);
  decl->line = line;
  decl->file = file;
  return true;
}

double KrlGet(const KrlAggregate& a, const char* key, const std::string& file, int line, const char* what) {
  const auto found = a.find(key);
  WAAM_THROW_UNLESS(found != a.end(), file << ":" << line << ": " << what << " lacks " << key);
  return found->second;
}

Eigen::Isometry3d KrlPose(const KrlAggregate& a, const std::string& file, int line) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(KrlGet(a, "X", file, line, "position"), KrlGet(a, "Y", file, line, "position"),
                                    KrlGet(a, "Z", file, line, "position"));
  X.linear() = internal::RotationZyx(KrlGet(a, "A", file, line, "position") * kPi / 180.0,
                                     KrlGet(a, "B", file, line, "position") * kPi / 180.0,
                                     KrlGet(a, "C", file, line, "position") * kPi / 180.0);
  return X;
}

}  // namespace

ParsedProgram ReadKukaKrl(std::string_view src, std::string_view dat, const std::string& src_file,
                          const std::string& dat_file) {
  ParsedProgram program;
  program.format = ProgramFormat::kKukaKrl;
  internal::WarningList warnings;
  std::map<std::string, KrlDecl> decls;
  const std::vector<std::string_view> dat_lines = internal::SplitProgramLines(dat, dat_file);
  for (std::size_t li = 0; li < dat_lines.size(); ++li) {
    std::string_view l = dat_lines[li];
    l = TrimBlank(l.substr(0, l.find(';')));
    if (l.empty() || l.front() == '&') continue;
    std::string name;
    KrlDecl decl;
    if (ParseKrlDecl(l, dat_file, static_cast<int>(li) + 1, &name, &decl)) {
      internal::CheckMotionCount(decls.size(), dat_file, static_cast<int>(li) + 1);
      decls[name] = std::move(decl);
    }
  }

  const std::vector<std::string_view> lines = internal::SplitProgramLines(src, src_file);
  bool in_def = false, ended = false, arc_on = false;
  double vel_mm_s = 0.0;
  std::optional<Eigen::Isometry3d> X_RB;  // $BASE given as a frame in the program
  for (std::size_t li = 0; li < lines.size() && !ended; ++li) {
    const int line = static_cast<int>(li) + 1;
    std::string_view l = lines[li];
    l = TrimBlank(l.substr(0, l.find(';')));
    if (l.empty() || l.front() == '&') continue;
    const std::string u = Upper(l);
    const std::string first = u.substr(0, u.find_first_of(" \t(="));
    if (first == "DEF" || u.compare(0, 11, "GLOBAL DEF ") == 0) {
      WAAM_THROW_UNLESS(!in_def, src_file << ":" << line << ": DEF inside DEF");
      in_def = true;
      std::string_view rest = TrimBlank(l.substr(u.find("DEF") + 3));
      program.name = std::string(TrimBlank(rest.substr(0, rest.find('('))));
      continue;
    }
    WAAM_THROW_UNLESS(in_def, src_file << ":" << line << ": expected DEF <name>( ) before '"
                                       << std::string(l.substr(0, 30)) << "'");
    if (first == "END") {
      ended = true;
      continue;
    }
    std::string name;
    KrlDecl decl;
    if (first == "DECL" && ParseKrlDecl(l, src_file, line, &name, &decl)) {
      decls[name] = std::move(decl);
      continue;
    }
    if (first == "INI") continue;
    if (first == "BAS") {
      const std::size_t cp = u.find("#CP_PARAMS");
      const std::size_t vcp = u.find("#VEL_CP");
      if (cp != std::string::npos || vcp != std::string::npos) {
        const std::size_t comma = u.find(',', cp != std::string::npos ? cp : vcp);
        const std::size_t close = u.find(')', comma == std::string::npos ? 0 : comma);
        WAAM_THROW_UNLESS(comma != std::string::npos && close != std::string::npos,
                          src_file << ":" << line << ": BAS without its speed");
        vel_mm_s = 1000.0 * ParseProgramNumber(u.substr(comma + 1, close - comma - 1), src_file, line, "BAS speed");
      }
      continue;  // #INITMOV, #PTP_PARAMS, #TOOL, #BASE: no effect on the path
    }
    if (u[0] == '$') {
      const std::size_t eq = u.find('=');
      WAAM_THROW_UNLESS(eq != std::string::npos, src_file << ":" << line << ": system variable without a value");
      const std::string var = std::string(TrimBlank(std::string_view(u).substr(0, eq)));
      const std::string_view value = TrimBlank(l.substr(eq + 1));
      if (var == "$VEL.CP") {
        vel_mm_s = 1000.0 * ParseProgramNumber(value, src_file, line, "$VEL.CP");
        WAAM_THROW_UNLESS(vel_mm_s > 0.0, src_file << ":" << line << ": $VEL.CP must be > 0");
      } else if (var == "$BASE") {
        if (!value.empty() && value.front() == '{') {
          X_RB = KrlPose(ParseKrlAggregate(value, src_file, line), src_file, line);
        } else {
          X_RB.reset();  // BASE_DATA[n]: the scenario's user frame
        }
      } else if (var.compare(0, 5, "$OUT[") == 0) {
        const std::string v = Upper(value);
        WAAM_THROW_UNLESS(v == "TRUE" || v == "FALSE", src_file << ":" << line << ": " << var << " must be TRUE or FALSE");
        if (var == "$OUT[1]") {
          arc_on = v == "TRUE";
        } else {
          warnings.Add("output " + var + " not executed", line);
        }
      }
      // $APO, $ACC, $VEL.ORI, $TOOL, $ORI_TYPE...: no effect on the path (the tool is the cell's)
      continue;
    }
    if (first == "ARC_ON" || first == "ARC_OFF") {
      arc_on = first == "ARC_ON";
      continue;
    }
    const bool ptp = first == "PTP", lin = first == "LIN", circ = first == "CIRC";
    if (!ptp && !lin && !circ) {
      warnings.Add("instruction " + first.substr(0, 24) + " not executed", line);
      continue;
    }
    internal::CheckMotionCount(program.motions.size(), src_file, line);
    // Targets: names or aggregates, separated by a comma for CIRC; approximation words after them.
    std::string_view rest = TrimBlank(l.substr(first.size()));
    std::vector<std::string> targets;
    while (!rest.empty() && targets.size() < (circ ? 2u : 1u)) {
      std::size_t end;
      if (rest.front() == '{') {
        end = rest.find('}');
        WAAM_THROW_UNLESS(end != std::string_view::npos, src_file << ":" << line << ": aggregate without its '}'");
        ++end;
      } else {
        end = rest.find_first_of(" \t,");
        if (end == std::string_view::npos) end = rest.size();
      }
      targets.emplace_back(rest.substr(0, end));
      rest = TrimBlank(rest.substr(end));
      if (!rest.empty() && rest.front() == ',') rest = TrimBlank(rest.substr(1));
    }
    WAAM_THROW_UNLESS(targets.size() == (circ ? 2u : 1u),
                      src_file << ":" << line << ": " << first << " needs " << (circ ? "an auxiliary and an end" : "a")
                               << " position");
    if (!rest.empty()) {
      const std::string word = Upper(rest.substr(0, rest.find_first_of(" \t")));
      if (word != "C_DIS" && word != "C_PTP" && word != "C_VEL" && word != "C_ORI") {
        warnings.Add(first + " option " + word.substr(0, 16) + " not executed", line);
      }
    }
    auto resolve = [&](const std::string& t, KrlDecl* storage) -> const KrlDecl* {
      if (!t.empty() && t.front() == '{') {
        storage->value = ParseKrlAggregate(t, src_file, line);
        storage->type = storage->value.count("A1") ? "E6AXIS" : "E6POS";
        storage->line = line;
        storage->file = src_file;
        return storage;
      }
      const auto found = decls.find(Upper(t));
      WAAM_THROW_UNLESS(found != decls.end(),
                        src_file << ":" << line << ": " << t << " is used but not declared in the .dat or the .src");
      return &found->second;
    };
    KrlDecl storage[2];
    const KrlDecl* target = resolve(targets.back(), &storage[0]);
    ProgramMotion m;
    m.line = line;
    m.kind = ptp ? MotionKind::kJoint : (lin ? MotionKind::kLinear : MotionKind::kCircular);
    const KrlAggregate& a = target->value;
    if (target->type == "E6AXIS" || target->type == "AXIS") {
      m.has_joints = true;
      for (int j = 0; j < 6; ++j) {
        static const char* const kAxes[6] = {"A1", "A2", "A3", "A4", "A5", "A6"};
        m.q[j] = KrlGet(a, kAxes[j], target->file, target->line, "axis position") * kPi / 180.0;
      }
    } else {
      m.has_pose = true;
      const Eigen::Isometry3d X = KrlPose(a, target->file, target->line);
      m.frame = X_RB ? TargetFrame::kRobot : TargetFrame::kUser;
      m.X_UT = X_RB ? Eigen::Isometry3d(*X_RB * X) : X;
      if (a.count("S")) {
        const double s = a.at("S");
        if (s >= 0.0 && s <= 7.0) m.config = static_cast<int>(s);
      }
    }
    if (a.count("E1")) {
      m.has_positioner = true;
      m.positioner_numbered = true;
      m.tilt_rad = a.at("E1") * kPi / 180.0;
      m.rotation_rad = a.count("E2") ? a.at("E2") * kPi / 180.0 : 0.0;
    }
    if (circ) {
      const KrlDecl* aux = resolve(targets.front(), &storage[1]);
      const Eigen::Isometry3d X = KrlPose(aux->value, aux->file, aux->line);
      m.has_via = true;
      m.via = X_RB ? Eigen::Vector3d(*X_RB * X.translation()) : X.translation();
    }
    m.speed_mm_s = ptp ? 0.0 : vel_mm_s;
    if (!ptp && vel_mm_s <= 0.0) warnings.Add("CP motion before any $VEL.CP: the scenario's speed used", line);
    m.weld = arc_on && !ptp;
    program.motions.push_back(m);
  }
  WAAM_THROW_UNLESS(in_def, src_file << ": not a KRL program (no DEF line)");
  WAAM_THROW_UNLESS(ended, src_file << ":" << lines.size() << ": no END: the program is truncated");
  program.warnings = warnings.Take();
  return program;
}

}  // namespace waam::planner
