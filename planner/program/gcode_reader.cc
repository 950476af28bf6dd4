// G-code reader: each line lexed into words (a letter and a number), then run in the controllers' order of execution
// by a small function per kind (feed, arc signals, M codes, dwell, modes, G92, motion), with the modal state.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/program/program_reader.h"

namespace waam::planner {
namespace {

using internal::ParseProgramNumber;

// One word: a letter (or a named word as Sinumerik's A3= or ISG's XR=) and its value.
struct GcodeWord {
  std::string name;  // "X", "G", "A3", "XR"
  double value = 0.0;
};

// A signal of program.gcode.arc_on / arc_off: its words, the first the code.
using GcodeSignal = std::vector<GcodeWord>;

bool IsAlpha(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }
bool IsDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }
bool IsBlank(char c) { return c == ' ' || c == '\t'; }

// "G90.1", "M62", "T2".
std::string CodeText(const std::string& name, double value) {
  char buf[48];
  std::snprintf(buf, sizeof(buf), "%s%.6g", name.c_str(), value);
  return buf;
}

// The line without its comments (';' to the end, '( ... )'), its block-delete '/' and '%' marks, and a '*' checksum.
std::string StripGcodeLine(std::string_view raw, const std::string& file, int line, internal::WarningList* warnings) {
  std::string out;
  std::size_t i = 0;
  while (i < raw.size() && IsBlank(raw[i])) ++i;
  if (i < raw.size() && raw[i] == '/') {
    warnings->Add("block delete '/' line run (the controller's switch decides)", line);
    ++i;
  }
  for (; i < raw.size(); ++i) {
    const char c = raw[i];
    if (c == ';') break;
    if (c == '*') break;  // RepRap checksum: N123 G1 X1 *71
    if (c == '(') {
      const std::size_t close = raw.find(')', i);
      WAAM_THROW_UNLESS(close != std::string_view::npos, file << ":" << line << ": comment '(' without its ')'");
      i = close;
      out += ' ';
      continue;
    }
    out += c == '%' ? ' ' : c;
  }
  return out;
}

// The number at text[*at] (after an optional '=' and blanks), or InputError "<name> 'text' is not a finite number".
double LexGcodeNumber(std::string_view text, std::size_t* at, const std::string& name, const std::string& file,
                      int line) {
  std::size_t i = *at;
  while (i < text.size() && IsBlank(text[i])) ++i;
  if (i < text.size() && text[i] == '=') ++i;
  while (i < text.size() && IsBlank(text[i])) ++i;
  std::size_t end = i;
  while (end < text.size() && (IsDigit(text[end]) || text[end] == '.' || text[end] == '-' || text[end] == '+')) ++end;
  if (end == i) {
    std::size_t stop = i;
    while (stop < text.size() && !IsBlank(text[stop]) && stop - i < 12) ++stop;
    WAAM_THROW(file << ":" << line << ": " << name << " '" << std::string(text.substr(i, stop - i))
                    << "' is not a finite number");
  }
  *at = end;
  return ParseProgramNumber(text.substr(i, end - i), file, line, name);
}

// The words of a stripped line. A word of several letters not followed by '=' (TRAORI, ISG's #TRAFO, LinuxCNC's
// #1 = 2 and O-words) is a statement the twin does not execute: warned, and the rest of the line with it.
std::vector<GcodeWord> LexGcodeWords(std::string_view text, const std::string& file, int line,
                                     internal::WarningList* warnings) {
  std::vector<GcodeWord> words;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (IsBlank(c) || c == '\r') {
      ++i;
      continue;
    }
    std::size_t k = i;
    if (c == '#') ++k;
    while (k < text.size() && (IsAlpha(text[k]) || text[k] == '_' ||
                               (text[k] == '.' && k + 1 < text.size() && IsAlpha(text[k + 1])))) {
      ++k;
    }
    std::size_t after = k;
    while (after < text.size() && IsBlank(text[after])) ++after;
    const bool named = after < text.size() && text[after] == '=';
    // X NaN, X inf: a word whose value is no finite number.
    const std::string tail = k - i > 1 ? internal::Upper(text.substr(i + 1, k - i - 1)) : "";
    if (tail == "NAN" || tail == "INF" || tail == "INFINITY") {
      WAAM_THROW(file << ":" << line << ": " << static_cast<char>(std::toupper(static_cast<unsigned char>(c))) << " '"
                      << std::string(text.substr(i + 1, k - i - 1)) << "' is not a finite number");
    }
    if (k == i || (k - i > 1 && !named) || c == '#' || c == 'O' || c == 'o') {
      WAAM_THROW_UNLESS(k > i, file << ":" << line << ": unexpected '" << c
                                    << "' (a G-code word is a letter and a number)");
      std::string what = internal::Upper(text.substr(i, std::min<std::size_t>(k - i, 16)));
      warnings->Add("statement " + what + " not executed (rest of its line skipped)", line);
      break;
    }
    GcodeWord w;
    w.name = internal::Upper(text.substr(i, k - i));
    // Sinumerik's A3=: a letter, digits, '='.
    std::size_t d = k;
    while (d < text.size() && IsDigit(text[d])) ++d;
    if (!named && d > k && d < text.size() && text[d] == '=') w.name += std::string(text.substr(k, d - k)), k = d;
    i = k;
    w.value = LexGcodeNumber(text, &i, w.name, file, line);
    words.push_back(w);
    if (w.name == "M" && (w.value == 117.0 || w.value == 118.0)) break;  // M117 / M118 <message text>
  }
  return words;
}

// The modal state of the controller while the program runs.
struct GcodeState {
  int motion = 0;             // G0..G3
  int plane = 17;             // G17 XY, G18 ZX, G19 YZ
  bool relative = false;      // G91
  bool arc_centre_absolute = false;  // G90.1
  double unit = 1.0;          // mm per program length unit (G20: 25.4)
  double feed_mm_s = 0.0;     // modal F
  double raw_feed = 0.0;      // modal F as written
  bool arc_on = false;
  bool e_relative = false;    // M83 (or G91)
  double last_e = 0.0;
  Eigen::Vector3d pos = Eigen::Vector3d::Zero();     // part frame, mm
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // G92: part = program coordinates + offset, mm
  double tilt_deg = 0.0, rotation_deg = 0.0;
  Eigen::Vector3d tool = Eigen::Vector3d::UnitZ();
  bool any_position = false;
  bool ended = false;         // M2 / M30
};

struct GcodeRun {
  const std::string& file;
  const GcodeReadOptions& options;
  ParsedProgram& program;
  internal::WarningList& warnings;
  std::vector<GcodeSignal> on, off;
  GcodeState s;
  std::vector<double> weld_feeds;  // F as written on weld moves, for the unit check
  std::vector<double> p_dwells;    // G4 P as written, for the unit check
};

// One block (line) of words.
struct GcodeBlock {
  std::vector<GcodeWord> words;
  int line = 0;
  const GcodeWord* Find(const char* name) const {
    for (const GcodeWord& w : words) {
      if (w.name == name) return &w;
    }
    return nullptr;
  }
  bool HasCode(const char* letter, double code) const {
    for (const GcodeWord& w : words) {
      if (w.name == letter && std::abs(w.value - code) < 1e-9) return true;
    }
    return false;
  }
};

GcodeSignal ParseGcodeSignal(std::string_view text, const std::string& where) {
  internal::WarningList ignored;
  GcodeSignal words;
  try {
    words = LexGcodeWords(StripGcodeLine(text, where, 0, &ignored), where, 0, &ignored);
  } catch (const InputError&) {
    words.clear();
  }
  bool valid = !words.empty() && (words[0].name == "M" || words[0].name == "G") && ignored.Take().empty();
  for (const GcodeWord& w : words) valid = valid && w.name.size() == 1;
  WAAM_THROW_UNLESS(valid, where << " '" << std::string(text.substr(0, 24))
                                 << "': an arc signal is a G or M code and parameter words, as M3, G82 or M62 P1");
  return words;
}

// True when every word of the signal is on the line (its parameters with the same values).
bool BlockHasSignal(const GcodeBlock& block, const GcodeSignal& signal) {
  for (const GcodeWord& s : signal) {
    if (!block.HasCode(s.name.c_str(), s.value)) return false;
  }
  return true;
}

bool IsSignalCode(const GcodeRun& run, const GcodeWord& w) {
  for (const auto* list : {&run.on, &run.off}) {
    for (const GcodeSignal& s : *list) {
      if (s[0].name == w.name && std::abs(s[0].value - w.value) < 1e-9) return true;
    }
  }
  return false;
}

// F: the modal feed, in options.feed_unit and the program's length unit.
void ExecGcodeFeed(GcodeRun& run, const GcodeBlock& block) {
  const GcodeWord* f = block.Find("F");
  if (f == nullptr || block.HasCode("G", 4)) return;  // Sinumerik's G4 F is a time
  WAAM_THROW_UNLESS(f->value >= 0.0, run.file << ":" << block.line << ": F" << f->value << " must be >= 0");
  // F0 programs no feed: no move can run at it, and the controllers that take it (ORNL's Wolf syntax writes
  // M5T2D1F0 before each layer's travel) run the next moves at the feed in force; LinuxCNC refuses a G1 at zero
  // feed. The modal feed stays, warned.
  if (f->value == 0.0) {
    run.warnings.Add("F0 programs no feed: the moves keep the feed in force", block.line);
    return;
  }
  const double per_s = run.options.feed_unit == GcodeFeedUnit::kMmPerS ? 1.0 : 1.0 / 60.0;
  run.s.feed_mm_s = f->value * run.s.unit * per_s;
  run.s.raw_feed = f->value;
}

// M codes: the arc signals first (off before on when a line holds both), then extrusion modes, program end and
// stops; any other M code is warned.
void ExecGcodeMCodes(GcodeRun& run, const GcodeBlock& block) {
  for (const GcodeSignal& s : run.off) {
    if (BlockHasSignal(block, s)) run.s.arc_on = false;
  }
  for (const GcodeSignal& s : run.on) {
    if (BlockHasSignal(block, s)) run.s.arc_on = true;
  }
  for (const GcodeWord& w : block.words) {
    if (w.name != "M" || IsSignalCode(run, w)) continue;
    const double m = w.value;
    if (m == 82 || m == 83) {
      run.s.e_relative = m == 83;
    } else if (m == 2 || m == 30) {
      run.s.ended = true;
    } else if (m == 0 || m == 1 || m == 60) {
      run.warnings.Add(CodeText("M", m) + " program stop: the operator's time is not in the timeline", block.line);
    } else if (m == 117 || m == 118 || m == 400 || m == 84 || m == 17 || m == 18) {
      // message, wait for the moves to finish, steppers on / off: no time of their own
    } else {
      run.warnings.Add(CodeText("M", m) + " not executed", block.line);
    }
  }
}

// G4 dwell: P in options.dwell_p_unit, S and X (FANUC G04 X) and Sinumerik's F in seconds; the torch waits at its
// last target. No axis moves on the line.
void ExecGcodeDwell(GcodeRun& run, const GcodeBlock& block) {
  double seconds = 0.0;
  bool timed = false;
  for (const GcodeWord& w : block.words) {
    const std::string& n = w.name;
    if (n == "G" && w.value != 4.0 && (w.value <= 3.0 || w.value == 28.0)) {
      WAAM_THROW(run.file << ":" << block.line << ": G4 shares its line with G" << w.value << ": a dwell stands alone");
    }
    if (n == "Y" || n == "Z" || n == "A" || n == "C" || n == "E" || n == "I" || n == "J" || n == "K") {
      WAAM_THROW(run.file << ":" << block.line << ": G4 with the axis word " << n << ": a dwell moves no axis");
    }
    if (n != "P" && n != "S" && n != "X" && n != "F") continue;
    WAAM_THROW_UNLESS(w.value >= 0.0, run.file << ":" << block.line << ": G4 " << n << w.value << " must be >= 0");
    const bool ms = n == "P" && run.options.dwell_p_unit == GcodeDwellUnit::kMs;
    if (n == "P") run.p_dwells.push_back(w.value);
    seconds += ms ? w.value / 1000.0 : w.value;
    timed = true;
  }
  if (!timed) {
    run.warnings.Add("G4 without a time (waits for the moves to finish): no wait", block.line);
    return;
  }
  internal::AddDwell(&run.program.motions, seconds, block.line, &run.warnings);
}

// G92: the current point takes the given coordinates (X Y Z in the program's unit; E the extruded length);
// G92.1 clears the offsets.
void ExecGcodeSetPosition(GcodeRun& run, const GcodeBlock& block, bool clear) {
  if (clear) {
    run.s.offset.setZero();
    return;
  }
  for (const GcodeWord& w : block.words) {
    if (w.name.size() == 1 && w.name[0] >= 'X' && w.name[0] <= 'Z') {
      const int k = w.name[0] - 'X';
      run.s.offset[k] = run.s.pos[k] - w.value * run.s.unit;
    } else if (w.name == "E") {
      run.s.last_e = w.value;
    }
  }
}

// Non-motion G codes: modes, units, planes, G92; returns true when the line sets positions instead of moving (G92,
// G28, G53 lines).
bool ExecGcodeModes(GcodeRun& run, const GcodeBlock& block) {
  bool no_move = false;
  for (const GcodeWord& w : block.words) {
    if (w.name != "G" || IsSignalCode(run, w)) continue;
    const double g = w.value;
    WAAM_THROW_UNLESS(g >= 0.0 && g < 10000.0, run.file << ":" << block.line << ": G" << g << " is not a G code");
    if (g == 0 || g == 1 || g == 2 || g == 3) run.s.motion = static_cast<int>(g);
    else if (g == 17 || g == 18 || g == 19) run.s.plane = static_cast<int>(g);
    else if (g == 20 || g == 21) run.s.unit = g == 20 ? 25.4 : 1.0;
    else if (g == 90 || g == 91) run.s.relative = run.s.e_relative = g == 91;
    else if (std::abs(g - 90.1) < 1e-9 || std::abs(g - 91.1) < 1e-9) run.s.arc_centre_absolute = g < 91.0;
    else if (g == 92 || std::abs(g - 92.1) < 1e-9) ExecGcodeSetPosition(run, block, g != 92), no_move = true;
    else if (g == 28 || g == 53) {
      run.warnings.Add(CodeText("G", g) + (g == 28 ? " (home)" : " (machine coordinates)") +
                           " not executed: positions stay in the part frame",
                       block.line);
      no_move = true;
    } else if (g == 93) {
      run.warnings.Add("G93 inverse-time feed not followed: F read as a feed", block.line);
    } else if (g == 4 || g == 94 || g == 40 || g == 49 || g == 80 || g == 61 || g == 64 || (g >= 54 && g <= 59.9)) {
      // dwell (run above), feed per minute, no compensation, canned cycles off, path mode, work offsets (positions are the part's)
    } else {
      run.warnings.Add(CodeText("G", g) + " not executed", block.line);
    }
  }
  return no_move;
}

// The arc's centre in the plane's two coordinates from I J K (relative to the start or, G90.1, absolute) or R.
Eigen::Vector2d GcodeArcCentre(GcodeRun& run, const GcodeBlock& block, const Eigen::Vector2d& a,
                               const Eigen::Vector2d& b, const int axes[2], bool clockwise) {
  const char* const kOffsets[3] = {"I", "J", "K"};
  const std::string where = run.file + ":" + std::to_string(block.line) + ": G" + (clockwise ? "2" : "3");
  if (const GcodeWord* r = block.Find("R")) {
    const double radius = std::abs(r->value) * run.s.unit, half = (b - a).norm() / 2.0;
    WAAM_THROW_UNLESS(half > 1e-9, where << " with R from its start to the same point: R arcs cannot be full circles");
    WAAM_THROW_UNLESS(radius >= half - 1e-6 * std::max(1.0, radius),
                      where << " R" << r->value << " is shorter than half the distance to the end point");
    const double h = std::sqrt(std::max(0.0, radius * radius - half * half));
    const Eigen::Vector2d mid = (a + b) / 2.0, dir = (b - a) / (2.0 * half);
    // The centre on the side that makes the arc the short one (R > 0) or the long one (R < 0).
    const double side = (clockwise ? -1.0 : 1.0) * (r->value < 0.0 ? -1.0 : 1.0);
    return mid + side * h * Eigen::Vector2d(-dir.y(), dir.x());
  }
  Eigen::Vector2d c = run.s.arc_centre_absolute ? Eigen::Vector2d::Zero() : a;
  bool any = false;
  for (int k = 0; k < 2; ++k) {
    if (const GcodeWord* w = block.Find(kOffsets[axes[k]])) {
      c[k] += w->value * run.s.unit + (run.s.arc_centre_absolute ? run.s.offset[axes[k]] : 0.0);
      any = true;
    } else if (run.s.arc_centre_absolute) {
      c[k] = a[k];
    }
  }
  WAAM_THROW_UNLESS(any, where << " needs its centre (" << kOffsets[axes[0]] << " " << kOffsets[axes[1]]
                               << ") or a radius R in the plane of G" << run.s.plane);
  const double r0 = (a - c).norm(), r1 = (b - c).norm(), dr = std::abs(r1 - r0);
  WAAM_THROW_UNLESS(r0 > 1e-9, where << " arc of radius 0");
  // Grbl refuses past 0.005 mm and 0.1 %, LinuxCNC past 0.0127 mm; a rounded export is warned, a wrong centre refused.
  WAAM_THROW_UNLESS(dr <= 0.05 || dr <= 1e-3 * r0, where << ": the end point is " << dr
                                                         << " mm off the circle about the centre (radius " << r0 << ")");
  if (dr > 0.005 && dr > 1e-3 * r0) run.warnings.Add("G2/G3 end point off its circle by more than 0.005 mm", block.line);
  return c;
}

// G2 / G3 from s.pos to `target`: circular motions of at most 90 degrees each (a via point in the middle), the axis
// normal to the plane running linearly (a helix).
void AddGcodeArc(GcodeRun& run, const GcodeBlock& block, const ProgramMotion& m, const Eigen::Vector3d& target) {
  static const int kPlaneAxes[3][3] = {{0, 1, 2}, {2, 0, 1}, {1, 2, 0}};  // G17 XY, G18 ZX, G19 YZ; then the normal
  const int* ax = kPlaneAxes[run.s.plane - 17];
  const Eigen::Vector3d& p0 = run.s.pos;
  const Eigen::Vector2d a(p0[ax[0]], p0[ax[1]]), b(target[ax[0]], target[ax[1]]);
  const bool clockwise = run.s.motion == 2;
  const Eigen::Vector2d c = GcodeArcCentre(run, block, a, b, ax, clockwise);
  const double r = (a - c).norm();
  const double a0 = std::atan2(a.y() - c.y(), a.x() - c.x());
  double sweep = std::atan2(b.y() - c.y(), b.x() - c.x()) - a0;
  if (clockwise) {
    while (sweep >= -1e-12) sweep -= 2.0 * kPi;
  } else {
    while (sweep <= 1e-12) sweep += 2.0 * kPi;
  }
  auto on_arc = [&](double f) {
    Eigen::Vector3d p;
    p[ax[0]] = c.x() + r * std::cos(a0 + f * sweep);
    p[ax[1]] = c.y() + r * std::sin(a0 + f * sweep);
    p[ax[2]] = p0[ax[2]] + f * (target[ax[2]] - p0[ax[2]]);
    return p;
  };
  const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / (kPi / 2.0) - 1e-9)));
  for (int k = 1; k <= pieces; ++k) {
    internal::CheckMotionCount(run.program.motions.size(), run.file, block.line);
    ProgramMotion piece = m;
    piece.kind = MotionKind::kCircular;
    piece.has_via = true;
    piece.via = on_arc((k - 0.5) / pieces);
    piece.X_UT.translation() = k == pieces ? target : on_arc(static_cast<double>(k) / pieces);
    run.program.motions.push_back(piece);
  }
}

// The axis words of a motion line: the target (part frame, mm), the positioner angles and the tool direction; false
// when the line names no axis.
bool ReadGcodeTarget(GcodeRun& run, const GcodeBlock& block, Eigen::Vector3d* target, double* tilt, double* rotation,
                     Eigen::Vector3d* tool) {
  GcodeState& s = run.s;
  bool axis = false;
  for (const GcodeWord& w : block.words) {
    const std::string& n = w.name;
    if (n == "X" || n == "Y" || n == "Z") {
      const int k = n[0] - 'X';
      (*target)[k] = s.relative ? (*target)[k] + w.value * s.unit : w.value * s.unit + s.offset[k];
      axis = true;
    } else if (n == "A" || n == "C") {
      double& angle = n == "A" ? *tilt : *rotation;
      angle = (s.relative ? angle : 0.0) + w.value;
      axis = true;
    } else if (n == "A3" || n == "B3" || n == "C3") {
      (*tool)[n[0] - 'A'] = w.value;
      axis = true;
      WAAM_THROW_UNLESS(std::isfinite(w.value), run.file << ":" << block.line << ": " << n << " is not finite");
    } else if (n != "G" && n != "M" && n != "F" && n != "E" && n != "I" && n != "J" && n != "K" && n != "R" &&
               n != "N" && n != "S" && n != "P" && n != "H" && n != "D" && n != "T") {
      run.warnings.Add("word " + n + " not executed", block.line);
    }
  }
  if (block.Find("A3") || block.Find("B3") || block.Find("C3")) {
    WAAM_THROW_UNLESS(tool->norm() > 1e-9, run.file << ":" << block.line << ": tool direction A3 B3 C3 of length 0");
    tool->normalize();
  }
  return axis;
}

// A motion line in the modal G0..G3: the move, the weld flag (arc on, or a growing E), the feed.
void ExecGcodeMotion(GcodeRun& run, const GcodeBlock& block) {
  GcodeState& s = run.s;
  Eigen::Vector3d target = s.pos, tool = s.tool;
  double tilt = s.tilt_deg, rotation = s.rotation_deg;
  const GcodeWord* e = block.Find("E");
  if (!ReadGcodeTarget(run, block, &target, &tilt, &rotation, &tool)) {
    if (e != nullptr && !s.e_relative) s.last_e = e->value;  // a retract or prime in place
    return;
  }
  internal::CheckMotionCount(run.program.motions.size(), run.file, block.line);
  const bool extruding = e != nullptr && (s.e_relative ? e->value > 0.0 : e->value > s.last_e);
  if (e != nullptr && !s.e_relative) s.last_e = e->value;
  ProgramMotion m;
  m.line = block.line;
  m.kind = s.motion == 0 ? MotionKind::kJoint : MotionKind::kLinear;
  m.has_pose = true;
  m.frame = TargetFrame::kPart;
  m.X_UT.translation() = target;
  m.X_UT.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), -tool).toRotationMatrix();
  m.has_positioner = true;
  m.tilt_rad = tilt * kPi / 180.0;
  m.rotation_rad = rotation * kPi / 180.0;
  m.speed_mm_s = s.motion == 0 ? 0.0 : s.feed_mm_s;
  m.weld = s.motion != 0 && (s.arc_on || extruding);
  if (m.weld && s.raw_feed > 0.0) run.weld_feeds.push_back(s.raw_feed);
  if (s.motion >= 2 && s.any_position) {
    AddGcodeArc(run, block, m, target);
  } else {
    if (s.motion >= 2) run.warnings.Add("G2/G3 before any known position followed as a linear move", block.line);
    run.program.motions.push_back(m);
  }
  s.pos = target, s.tilt_deg = tilt, s.rotation_deg = rotation, s.tool = tool, s.any_position = true;
}

// Runs one line in the order of execution of RS274/NGC (LinuxCNC's manual, "Order of Execution"): feed, M codes
// (arc signals), dwell, modes and G92, then the motion.
void ExecGcodeBlock(GcodeRun& run, const GcodeBlock& block) {
  for (const GcodeWord& w : block.words) {
    WAAM_THROW_UNLESS((w.name != "G" && w.name != "M") || (w.value >= 0.0 && w.value < 10000.0),
                      run.file << ":" << block.line << ": " << w.name << w.value << " is not a G- or M-code");
    if (w.name == "T") run.warnings.Add(CodeText("T", w.value) + " tool select not executed: the cell's torch", block.line);
  }
  ExecGcodeFeed(run, block);
  ExecGcodeMCodes(run, block);
  const bool dwell = block.HasCode("G", 4) && !IsSignalCode(run, {"G", 4.0});
  if (dwell) ExecGcodeDwell(run, block);
  const bool no_move = ExecGcodeModes(run, block);
  if (!dwell && !no_move) ExecGcodeMotion(run, block);
}

// The median of `values` as written, for the unit checks.
double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Warns when the weld feeds or the G4 P dwells look like the other unit: feeds below 60 read as mm/min (under
// 1 mm/s, no arc travels that slowly) or above 200 read as mm/s (12 m/min, beyond any WAAM deposit); P dwells all
// from 5 to under 1000 read as ms (interpass dwells of under a second) or over 10000 read as s (hours).
void CheckGcodeUnits(const GcodeRun& run, internal::WarningList* warnings) {
  const GcodeReadOptions& o = run.options;
  if (!run.weld_feeds.empty()) {
    const double f = Median(run.weld_feeds);
    const std::string median = "weld feeds (median F" + std::to_string(f).substr(0, 8) + ")";
    if (o.feed_unit == GcodeFeedUnit::kMmPerMin && f < 60.0) {
      warnings->Add(median + " look like mm/s: set program.gcode.feed_unit: mm_per_s if the controller reads them so", 1);
    } else if (o.feed_unit == GcodeFeedUnit::kMmPerS && f > 200.0) {
      warnings->Add(median + " look like mm/min: program.gcode.feed_unit is mm_per_s", 1);
    }
  }
  if (run.p_dwells.empty()) return;
  const double most = *std::max_element(run.p_dwells.begin(), run.p_dwells.end());
  if (o.dwell_p_unit == GcodeDwellUnit::kMs && most < 1000.0 && most >= 5.0) {
    warnings->Add("G4 P dwells (at most P" + std::to_string(most).substr(0, 8) +
                      ") read as ms are all under a second: set program.gcode.dwell_p_unit: s if the controller "
                      "reads P in seconds (LinuxCNC, Grbl)",
                  1);
  } else if (o.dwell_p_unit == GcodeDwellUnit::kS && most > 10000.0) {
    warnings->Add("G4 P dwells (up to P" + std::to_string(most).substr(0, 8) +
                      ") read as s last hours: program.gcode.dwell_p_unit is s",
                  1);
  }
}

}  // namespace

void CheckGcodeSignal(std::string_view text, const std::string& where) { (void)ParseGcodeSignal(text, where); }

ParsedProgram ReadGcode(std::string_view text, const std::string& file, const GcodeReadOptions& options) {
  const std::vector<std::string_view> lines = internal::SplitProgramLines(text, file);
  ParsedProgram program;
  program.format = ProgramFormat::kGcode;
  program.name = std::filesystem::path(file).stem().string();
  internal::WarningList warnings;
  GcodeRun run{file, options, program, warnings, {}, {}, {}, {}, {}};
  for (const std::string& s : options.arc_on) run.on.push_back(ParseGcodeSignal(s, "program.gcode.arc_on"));
  for (const std::string& s : options.arc_off) run.off.push_back(ParseGcodeSignal(s, "program.gcode.arc_off"));
  for (std::size_t li = 0; li < lines.size(); ++li) {
    GcodeBlock block;
    block.line = static_cast<int>(li) + 1;
    block.words = LexGcodeWords(StripGcodeLine(lines[li], file, block.line, &warnings), file, block.line, &warnings);
    if (block.words.empty()) continue;
    if (run.s.ended) {
      warnings.Add("lines after the program's end (M2 / M30) not executed", block.line);
      break;
    }
    ExecGcodeBlock(run, block);
  }
  CheckGcodeUnits(run, &warnings);
  program.warnings = warnings.Take();
  return program;
}

}  // namespace waam::planner
