// FANUC LS (ASCII teach-pendant program) reader: /MN statements with continuation lines, /POS positions of both
// motion groups.
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/program/program_reader.h"

namespace waam::planner {
namespace {

using internal::ParseProgramNumber;
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
  int uf = -1;
};

struct LsStatement {
  std::string text;
  int line = 0;
};

// "N U T, 0, 0, 0" -> branch bits (bit 0 back, bit 1 elbow down, bit 2 wrist flipped), as FanucConfig writes them.
int ParseLsConfig(std::string_view text, const std::string& file, int line) {
  const std::string u = Upper(text);
  int bits = 0;
  int letters = 0;
  for (char c : u.substr(0, u.find(','))) {
    if (c == ' ') continue;
    ++letters;
    if (c == 'F') bits |= 4;
    else if (c == 'D') bits |= 2;
    else if (c == 'B') bits |= 1;
    else WAAM_THROW_UNLESS(c == 'N' || c == 'U' || c == 'T', file << ":" << line << ": CONFIG '" << std::string(text)
                                                                << "': expected letters N/F, U/D, T/B");
  }
  WAAM_THROW_UNLESS(letters == 3, file << ":" << line << ": CONFIG '" << std::string(text)
                                       << "': expected three letters (wrist N/F, elbow U/D, base T/B)");
  return bits;
}

// One "KEY = value unit" or "KEY : value" item of a /POS group line.
void ParseLsPositionItem(std::string_view item, int group, LsPosition* pos, const std::string& file, int line,
                         internal::WarningList* warnings) {
  item = TrimBlank(item);
  if (item.empty()) return;
  const std::size_t eq = item.find('=');
  if (eq == std::string_view::npos) {
    const std::size_t colon = item.find(':');
    WAAM_THROW_UNLESS(colon != std::string_view::npos,
                      file << ":" << line << ": /POS item '" << std::string(item.substr(0, 40)) << "' is not KEY = value");
    const std::string key = Upper(TrimBlank(item.substr(0, colon)));
    if (key == "UF" && group == 1) pos->uf = internal::ParseProgramInteger(item.substr(colon + 1), file, line, "UF", 0, 999);
    return;  // UT and the like: the tool is the cell's
  }
  const std::string key = Upper(TrimBlank(item.substr(0, eq)));
  std::string_view value = TrimBlank(item.substr(eq + 1));
  for (std::string_view unit : {"mm", "deg", "MM", "DEG"}) {
    if (value.size() >= unit.size() && value.substr(value.size() - unit.size()) == unit) {
      value = TrimBlank(value.substr(0, value.size() - unit.size()));
      break;
    }
  }
  const double v = ParseProgramNumber(value, file, line, key);
  static const char* const kCart[6] = {"X", "Y", "Z", "W", "P", "R"};
  if (group == 1) {
    for (int k = 0; k < 6; ++k) {
      if (key == kCart[k]) {
        pos->cartesian = true;
        pos->xyzwpr[k] = v;
        pos->xyzwpr_seen |= 1 << k;
        return;
      }
    }
    if (key.size() == 2 && key[0] == 'J' && key[1] >= '1' && key[1] <= '6') {
      pos->joints = true;
      pos->j[key[1] - '1'] = v;
      pos->j_seen |= 1 << (key[1] - '1');
      return;
    }
    warnings->Add("GP1 extended axis " + key + " ignored", line);
    return;
  }
  if (group == 2 && (key == "J1" || key == "J2")) {
    pos->gp2 = true;
    pos->gp2_j[key[1] - '1'] = v;
    pos->gp2_seen |= 1 << (key[1] - '1');
    return;
  }
  warnings->Add("motion group GP" + std::to_string(group) + " axis " + key + " ignored", line);
}

// Parses "P[12]" or "P[12:comment]" / "PR[3]" at `s[*at]`; returns the number, `*register_ref` when PR.
bool ParseLsRef(const std::string& s, std::size_t* at, int* number, bool* register_ref) {
  std::size_t i = *at;
  while (i < s.size() && s[i] == ' ') ++i;
  *register_ref = s.compare(i, 3, "PR[") == 0;
  if (!*register_ref && s.compare(i, 2, "P[") != 0) return false;
  i += *register_ref ? 3 : 2;
  const std::size_t close = s.find(']', i);
  if (close == std::string::npos) return false;
  const std::string inside = s.substr(i, std::min(s.find(':', i), close) - i);
  if (inside.empty() || inside.size() > 9) return false;
  for (char c : inside) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  *number = std::stoi(inside);
  *at = close + 1;
  return true;
}

}  // namespace

ParsedProgram ReadFanucLs(std::string_view text, const std::string& file) {
  const std::vector<std::string_view> lines = internal::SplitProgramLines(text, file);
  ParsedProgram program;
  program.format = ProgramFormat::kFanucLs;
  internal::WarningList warnings;
  std::vector<LsStatement> statements;
  std::map<int, LsPosition> positions;
  enum class Section { kNone, kAttr, kAppl, kMn, kPos, kEnd } section = Section::kNone;
  bool seen_prog = false;
  bool open_statement = false;
  for (std::size_t li = 0; li < lines.size(); ++li) {
    const int line = static_cast<int>(li) + 1;
    const std::string_view raw = lines[li];
    const std::string_view t = TrimBlank(raw);
    if (t.empty()) continue;
    if (t.front() == '/') {
      const std::string head = Upper(t.substr(0, t.find_first_of(" \t") == std::string_view::npos
                                                      ? t.size()
                                                      : t.find_first_of(" \t")));
      if (head == "/PROG") {
        seen_prog = true;
        program.name = std::string(TrimBlank(t.substr(5)));
        program.name = program.name.substr(0, program.name.find_first_of(" \t"));
        continue;
      }
      WAAM_THROW_UNLESS(seen_prog, file << ":" << line << ": expected /PROG <name> before " << head);
      WAAM_THROW_UNLESS(section != Section::kEnd, file << ":" << line << ": text after /END");
      if (head == "/ATTR") section = Section::kAttr;
      else if (head == "/APPL") section = Section::kAppl;
      else if (head == "/MN") section = Section::kMn;
      else if (head == "/POS") section = Section::kPos;
      else if (head == "/END") section = Section::kEnd;
      else WAAM_THROW(file << ":" << line << ": unknown section " << head);
      continue;
    }
    WAAM_THROW_UNLESS(seen_prog, file << ":" << line << ": expected /PROG <name> as the first line");
    if (section == Section::kMn) {
      // "  12:  L P[3] 40cm/min CNT100 ;" or a continuation "    :  P[5] 40cm/min CNT100 ;".
      const std::size_t colon = raw.find(':');
      WAAM_THROW_UNLESS(colon != std::string_view::npos,
                        file << ":" << line << ": /MN line is not 'n: instruction ;'");
      const std::string_view number = TrimBlank(raw.substr(0, colon));
      bool digits = true;
      for (char c : number) digits = digits && std::isdigit(static_cast<unsigned char>(c));
      WAAM_THROW_UNLESS(digits, file << ":" << line << ": /MN line is not 'n: instruction ;'");
      std::string_view body = TrimBlank(raw.substr(colon + 1));
      if (number.empty() && open_statement) {
        statements.back().text += ' ';
      } else {
        WAAM_THROW_UNLESS(!number.empty(), file << ":" << line << ": continuation line without a statement before it");
        statements.push_back({"", line});
      }
      open_statement = true;
      if (!body.empty() && body.back() == ';') {
        body.remove_suffix(1);
        open_statement = false;
      }
      statements.back().text += std::string(TrimBlank(body));
    } else if (section == Section::kPos) {
      // P[n]{ or P[n:"comment"]{ ... };
      const std::string head = Upper(t);
      std::size_t at = 0;
      int number = 0;
      bool is_register = false;
      WAAM_THROW_UNLESS(ParseLsRef(head, &at, &number, &is_register) && !is_register &&
                            TrimBlank(t.substr(at)) == "{",
                        file << ":" << line << ": /POS expected 'P[n]{', got '" << std::string(t.substr(0, 40)) << "'");
      WAAM_THROW_UNLESS(positions.count(number) == 0, file << ":" << line << ": P[" << number << "] defined twice");
      internal::CheckMotionCount(positions.size(), file, line);
      LsPosition pos;
      pos.line = line;
      int group = 0;
      bool closed = false;
      for (++li; li < lines.size(); ++li) {
        const int pl = static_cast<int>(li) + 1;
        std::string_view body = TrimBlank(lines[li]);
        if (body.empty()) continue;
        if (body == "};") {
          closed = true;
          break;
        }
        WAAM_THROW_UNLESS(body.front() != '/',
                          file << ":" << pl << ": P[" << number << "] in /POS is not closed by '};' (truncated /POS)");
        const std::string ub = Upper(body);
        if (ub.size() >= 4 && ub.compare(0, 2, "GP") == 0 && ub.back() == ':') {
          group = internal::ParseProgramInteger(body.substr(2, body.size() - 3), file, pl, "motion group", 1, 8);
          continue;
        }
        WAAM_THROW_UNLESS(group > 0, file << ":" << pl << ": P[" << number << "] value before its GP1: line");
        std::string rest(body);
        const std::size_t config = Upper(rest).find("CONFIG");
        if (config != std::string::npos) {
          const std::size_t q1 = rest.find('\'', config);
          const std::size_t q2 = q1 == std::string::npos ? q1 : rest.find('\'', q1 + 1);
          WAAM_THROW_UNLESS(q2 != std::string::npos, file << ":" << pl << ": CONFIG without its quoted string");
          pos.config = ParseLsConfig(std::string_view(rest).substr(q1 + 1, q2 - q1 - 1), file, pl);
          rest.erase(config, q2 + 1 - config);
        }
        std::size_t start = 0;
        while (start <= rest.size()) {
          std::size_t comma = rest.find(',', start);
          if (comma == std::string::npos) comma = rest.size();
          ParseLsPositionItem(std::string_view(rest).substr(start, comma - start), group, &pos, file, pl, &warnings);
          start = comma + 1;
        }
      }
      WAAM_THROW_UNLESS(closed, file << ":" << pos.line << ": P[" << number
                                     << "] in /POS is not closed by '};' (truncated /POS)");
      WAAM_THROW_UNLESS(!pos.cartesian || pos.xyzwpr_seen == 63,
                        file << ":" << pos.line << ": P[" << number << "] lacks one of X, Y, Z, W, P, R");
      WAAM_THROW_UNLESS(!pos.joints || pos.j_seen == 63,
                        file << ":" << pos.line << ": P[" << number << "] lacks one of J1..J6");
      WAAM_THROW_UNLESS(pos.cartesian != pos.joints,
                        file << ":" << pos.line << ": P[" << number << "] needs GP1 as X..R or as J1..J6");
      positions[number] = pos;
    }
    // /ATTR and /APPL: header data the motion does not depend on.
  }
  WAAM_THROW_UNLESS(seen_prog, file << ": not a FANUC LS program (no /PROG line)");
  WAAM_THROW_UNLESS(section == Section::kEnd, file << ":" << lines.size() << ": no /END: the program is truncated");
  WAAM_THROW_UNLESS(!open_statement, file << ":" << statements.back().line << ": statement without its closing ';'");

  std::set<int> user_frames;
  bool arc_on = false;
  for (const LsStatement& st : statements) {
    const std::string u = Upper(st.text);
    if (u.empty() || u[0] == '!' || u.compare(0, 2, "//") == 0) continue;  // comment
    const bool motion = u.size() > 2 && (u[0] == 'J' || u[0] == 'L' || u[0] == 'C' || u[0] == 'A') && u[1] == ' ' &&
                        (u.find("P[", 2) != std::string::npos);
    if (!motion) {
      if (u.compare(0, 9, "ARC START") == 0) {
        arc_on = true;
      } else if (u.compare(0, 7, "ARC END") == 0) {
        arc_on = false;
      } else if (u.compare(0, 4, "LBL[") == 0) {
        // a label does nothing by itself
      } else if (u == "END") {
        break;  // the program ends here
      } else {
        std::size_t end = u.find_first_of(" [=(");
        std::string name = u.substr(0, std::min<std::size_t>(end, 24));
        if (name.empty()) name = u.substr(0, 24);
        warnings.Add("instruction " + name + " not executed", st.line);
      }
      continue;
    }
    internal::CheckMotionCount(program.motions.size(), file, st.line);
    ProgramMotion m;
    m.line = st.line;
    m.kind = u[0] == 'J' ? MotionKind::kJoint : (u[0] == 'L' ? MotionKind::kLinear : MotionKind::kCircular);
    std::size_t at = 1;
    int target = 0, via = 0;
    bool is_register = false;
    WAAM_THROW_UNLESS(ParseLsRef(u, &at, &target, &is_register),
                      file << ":" << st.line << ": motion without a P[n] or PR[n] position");
    if (u[0] == 'A') {
      warnings.Add("circular arc motion A not executed", st.line);
      continue;
    }
    if (m.kind == MotionKind::kCircular) {
      via = target;
      bool via_register = is_register;
      WAAM_THROW_UNLESS(ParseLsRef(u, &at, &target, &is_register),
                        file << ":" << st.line << ": circular motion C needs its via and end positions");
      is_register = is_register || via_register;
    }
    if (is_register) {
      warnings.Add("motion to a position register PR[n] not executed", st.line);
      continue;
    }
    // Speed.
    while (at < u.size() && u[at] == ' ') ++at;
    std::size_t speed_end = u.find(' ', at);
    if (speed_end == std::string::npos) speed_end = u.size();
    const std::string speed = u.substr(at, speed_end - at);
    at = speed_end;
    const std::size_t unit_at = speed.find_first_not_of("0123456789.");
    const std::string unit = unit_at == std::string::npos ? "" : speed.substr(unit_at);
    if (speed.compare(0, 2, "R[") == 0 || speed.compare(0, 3, "AR[") == 0) {
      warnings.Add("speed from a register: the scenario's speed used", st.line);
    } else if (speed == "MAX_SPEED" || unit == "%" || unit == "SEC" || unit == "DEG/SEC") {
      if (m.kind != MotionKind::kJoint) warnings.Add("speed " + unit + " of a Cartesian move: the scenario's speed used", st.line);
    } else {
      WAAM_THROW_UNLESS(unit_at != std::string::npos && unit_at > 0,
                        file << ":" << st.line << ": motion speed '" << speed << "' has no number and unit");
      const double v = ParseProgramNumber(speed.substr(0, unit_at), file, st.line, "speed");
      WAAM_THROW_UNLESS(v > 0.0, file << ":" << st.line << ": motion speed " << speed << " must be > 0");
      if (unit == "MM/SEC") m.speed_mm_s = v;
      else if (unit == "CM/MIN") m.speed_mm_s = v * 10.0 / 60.0;
      else if (unit == "INCH/MIN") m.speed_mm_s = v * 25.4 / 60.0;
      else WAAM_THROW(file << ":" << st.line << ": motion speed unit '" << unit << "' unknown");
    }
    // Termination and options.
    bool option_start = false, option_end = false;
    std::string options = u.substr(at);
    for (const char* arc : {"ARC START", "ARC END"}) {
      const std::size_t k = options.find(arc);
      if (k == std::string::npos) continue;
      (arc[4] == 'S' ? option_start : option_end) = true;
      const std::size_t close = options.find(']', k);
      options.erase(k, (close == std::string::npos ? options.size() : close + 1) - k);
    }
    std::size_t k = 0;
    while (k < options.size()) {
      while (k < options.size() && options[k] == ' ') ++k;
      std::size_t e = options.find(' ', k);
      if (e == std::string::npos) e = options.size();
      const std::string word = options.substr(k, e - k);
      k = e;
      if (word.empty() || word == "FINE" || word == "COORD" || word.compare(0, 3, "CNT") == 0 ||
          word.compare(0, 2, "CD") == 0) {
        continue;
      }
      warnings.Add("motion option " + word.substr(0, word.find_first_of("[,(")) + " not executed", st.line);
    }
    m.weld = option_start ? false : arc_on;
    if (option_start) arc_on = true;
    if (option_end) m.weld = true, arc_on = false;

    const auto found = positions.find(target);
    WAAM_THROW_UNLESS(found != positions.end(),
                      file << ":" << st.line << ": P[" << target << "] is used but not defined in /POS");
    const LsPosition& pos = found->second;
    if (pos.cartesian) {
      m.has_pose = true;
      m.frame = TargetFrame::kUser;
      m.X_UT.translation() = Eigen::Vector3d(pos.xyzwpr[0], pos.xyzwpr[1], pos.xyzwpr[2]);
      m.X_UT.linear() = internal::RotationZyx(pos.xyzwpr[5] * kPi / 180.0, pos.xyzwpr[4] * kPi / 180.0,
                                              pos.xyzwpr[3] * kPi / 180.0);
      m.config = pos.config;
      if (pos.uf >= 0) user_frames.insert(pos.uf);
    } else {
      m.has_joints = true;
      for (int j = 0; j < 6; ++j) m.q[j] = pos.j[j] * kPi / 180.0;
    }
    if (pos.gp2) {
      // J1 and J2 of a two-axis positioner, or J1 alone of a turntable.
      WAAM_THROW_UNLESS(pos.gp2_seen & 1, file << ":" << pos.line << ": P[" << target << "] GP2 needs J1");
      m.has_positioner = true;
      m.positioner_numbered = true;
      m.tilt_rad = pos.gp2_j[0] * kPi / 180.0;
      m.rotation_rad = pos.gp2_j[1] * kPi / 180.0;
    }
    if (m.kind == MotionKind::kCircular) {
      const auto v = positions.find(via);
      WAAM_THROW_UNLESS(v != positions.end(),
                        file << ":" << st.line << ": P[" << via << "] is used but not defined in /POS");
      WAAM_THROW_UNLESS(v->second.cartesian,
                        file << ":" << st.line << ": the via point P[" << via << "] of a C motion must be Cartesian");
      m.has_via = true;
      m.via = Eigen::Vector3d(v->second.xyzwpr[0], v->second.xyzwpr[1], v->second.xyzwpr[2]);
    }
    program.motions.push_back(m);
  }
  if (user_frames.size() > 1) {
    warnings.Add("positions in " + std::to_string(user_frames.size()) +
                     " user frames (UF): all taken as the scenario's program.frame",
                 1);
  }
  program.warnings = warnings.Take();
  return program;
}

}  // namespace waam::planner
