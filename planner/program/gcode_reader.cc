// G-code reader: modal motion, units, absolute/relative positions, arcs in the XY plane, arc on/off by M-codes or
// extrusion.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/program/program_reader.h"

namespace waam::planner {
namespace {

using internal::ParseProgramNumber;

struct GcodeWord {
  std::string name;  // "X", "G", "A3", ...
  double value = 0.0;
};

// The words of a line without its comments (";" to the end, "( ... )").
std::vector<GcodeWord> GcodeWords(std::string_view line, const std::string& file, int line_no) {
  std::vector<GcodeWord> words;
  std::size_t i = 0;
  while (i < line.size()) {
    const char c = line[i];
    if (c == ';') break;
    if (c == '(') {
      const std::size_t close = line.find(')', i);
      WAAM_THROW_UNLESS(close != std::string_view::npos, file << ":" << line_no << ": comment '(' without its ')'");
      i = close + 1;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c)) || c == '%') {
      ++i;
      continue;
    }
    WAAM_THROW_UNLESS(std::isalpha(static_cast<unsigned char>(c)),
                      file << ":" << line_no << ": unexpected '" << c << "' (a G-code word is a letter and a number)");
    GcodeWord w;
    w.name = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    ++i;
    // Sinumerik-style named values: A3=0.5.
    std::size_t k = i;
    while (k < line.size() && std::isdigit(static_cast<unsigned char>(line[k]))) ++k;
    if (k > i && k < line.size() && line[k] == '=') {
      w.name += std::string(line.substr(i, k - i));
      i = k + 1;
    } else if (i < line.size() && line[i] == '=') {
      ++i;
    }
    while (i < line.size() && line[i] == ' ') ++i;
    std::size_t end = i;
    while (end < line.size() && (std::isdigit(static_cast<unsigned char>(line[end])) || line[end] == '.' ||
                                 line[end] == '-' || line[end] == '+')) {
      ++end;
    }
    if (end == i) {
      // Not a number: say what stands there (NaN, inf, a variable).
      std::size_t stop = i;
      while (stop < line.size() && !std::isspace(static_cast<unsigned char>(line[stop])) && stop - i < 12) ++stop;
      WAAM_THROW(file << ":" << line_no << ": " << w.name << " '" << std::string(line.substr(i, stop - i))
                      << "' is not a finite number");
    }
    w.value = ParseProgramNumber(line.substr(i, end - i), file, line_no, w.name);
    i = end;
    words.push_back(w);
  }
  return words;
}

// "G92", "M7" (a code number below 10000).
std::string CodeName(char letter, double code) {
  char buf[16];
  std::snprintf(buf, sizeof(buf), "%c%d", letter, static_cast<int>(code));
  return buf;
}

}  // namespace

// G4 (dwell) on its own line: P in milliseconds, S or X in seconds (Marlin / RepRap and FANUC's G04); the torch
// waits at its last target. Returns false when the line is not a G4.
bool ReadGcodeDwell(const std::vector<GcodeWord>& words, const std::string& file, int line, ParsedProgram* program,
                    internal::WarningList* warnings) {
  bool g4 = false;
  for (const GcodeWord& w : words) g4 = g4 || (w.name == "G" && w.value == 4.0);
  if (!g4) return false;
  double seconds = 0.0;
  bool timed = false;
  for (const GcodeWord& w : words) {
    if (w.name == "G" || w.name == "N") {
      WAAM_THROW_UNLESS(w.name == "N" || w.value == 4.0,
                        file << ":" << line << ": G4 shares its line with G" << w.value << ": a dwell stands alone");
      continue;
    }
    WAAM_THROW_UNLESS(w.name == "P" || w.name == "S" || w.name == "X",
                      file << ":" << line << ": G4 takes P (ms), S or X (s), not " << w.name);
    WAAM_THROW_UNLESS(w.value >= 0.0, file << ":" << line << ": G4 " << w.name << w.value << " must be >= 0");
    if (w.name == "P" && w.value != std::floor(w.value)) {
      warnings->Add("G4 P with a fraction read as milliseconds (Marlin, FANUC; LinuxCNC and Grbl read seconds)", line);
    }
    seconds += w.name == "P" ? w.value / 1000.0 : w.value;
    timed = true;
  }
  if (!timed) {
    warnings->Add("G4 without a time (waits for the moves to finish): no wait", line);
    return true;
  }
  internal::AddDwell(&program->motions, seconds, line, warnings);
  return true;
}

// Warns when the weld feeds look like the other unit: below 60 read as mm/min (under 1 mm/s, no arc travels that
// slowly) or above 200 read as mm/s (12 m/min, beyond any WAAM deposit), as written, in the program's length unit.
void CheckGcodeFeedUnit(std::vector<double> feeds, GcodeFeedUnit unit, internal::WarningList* warnings) {
  if (feeds.empty()) return;
  std::sort(feeds.begin(), feeds.end());
  const double median = feeds[feeds.size() / 2];
  if (unit == GcodeFeedUnit::kMmPerMin && median < 60.0) {
    warnings->Add("weld feeds (median F" + std::to_string(median).substr(0, 8) +
                      ") look like mm/s: set program.gcode.feed_unit: mm_per_s if the controller reads them so",
                  1);
  } else if (unit == GcodeFeedUnit::kMmPerS && median > 200.0) {
    warnings->Add("weld feeds (median F" + std::to_string(median).substr(0, 8) +
                      ") look like mm/min: program.gcode.feed_unit is mm_per_s",
                  1);
  }
}

ParsedProgram ReadGcode(std::string_view text, const std::string& file, const GcodeReadOptions& options) {
  const std::vector<std::string_view> lines = internal::SplitProgramLines(text, file);
  ParsedProgram program;
  program.format = ProgramFormat::kGcode;
  program.name = std::filesystem::path(file).stem().string();
  internal::WarningList warnings;
  int mode = 0;             // modal motion G0..G3
  bool relative = false;    // G91
  double unit = 1.0;        // G20: 25.4
  double feed_mm_s = 0.0;   // modal F
  bool arc_on = false;
  double last_e = 0.0;
  bool e_relative = false;  // M83
  Eigen::Vector3d pos = Eigen::Vector3d::Zero();
  double tilt_deg = 0.0, rotation_deg = 0.0;
  Eigen::Vector3d tool = Eigen::Vector3d::UnitZ();
  bool any_position = false;
  double raw_feed = 0.0;    // modal F as written
  std::vector<double> weld_feeds;  // F as written on weld moves, for the unit check
  const double feed_scale = options.feed_unit == GcodeFeedUnit::kMmPerS ? 1.0 : 1.0 / 60.0;
  for (std::size_t li = 0; li < lines.size(); ++li) {
    const int line = static_cast<int>(li) + 1;
    const std::vector<GcodeWord> words = GcodeWords(lines[li], file, line);
    if (ReadGcodeDwell(words, file, line, &program, &warnings)) continue;
    bool axis = false, has_e = false;
    double e = 0.0;
    Eigen::Vector3d target = pos, centre_offset = Eigen::Vector3d::Zero();
    double tilt = tilt_deg, rotation = rotation_deg;
    Eigen::Vector3d tool_words = tool;
    bool tool_given = false, has_ij = false, has_r = false;
    for (const GcodeWord& w : words) {
      const std::string& n = w.name;
      WAAM_THROW_UNLESS((n != "G" && n != "M") || (w.value >= 0.0 && w.value < 10000.0),
                        file << ":" << line << ": " << n << w.value << " is not a G- or M-code");
      if (n == "G") {
        const double g = w.value;
        if (g == 0 || g == 1 || g == 2 || g == 3) mode = static_cast<int>(g);
        else if (g == 20) unit = 25.4;
        else if (g == 21) unit = 1.0;
        else if (g == 90) relative = false;
        else if (g == 91) relative = true;
        else if (g == 17 || g == 94 || g == 40 || g == 49 || g == 54 || g == 64 || g == 61) {
          // XY plane, feed per minute, no cutter or length compensation, first work offset, path mode
        } else warnings.Add(CodeName('G', g) + " not executed", line);
      } else if (n == "M") {
        const int m = static_cast<int>(w.value);
        if (m == options.arc_on_m) arc_on = true;
        else if (m == options.arc_off_m) arc_on = false;
        else if (m == 82) e_relative = false;
        else if (m == 83) e_relative = true;
        else if (m == 2 || m == 30) {
          // end of program
        } else warnings.Add(CodeName('M', m) + " not executed", line);
      } else if (n == "X" || n == "Y" || n == "Z") {
        const int k = n[0] - 'X';
        target[k] = (relative ? target[k] : 0.0) + w.value * unit;
        axis = true;
      } else if (n == "A") {
        tilt = (relative ? tilt : 0.0) + w.value, axis = true;
      } else if (n == "C") {
        rotation = (relative ? rotation : 0.0) + w.value, axis = true;
      } else if (n == "A3" || n == "B3" || n == "C3") {
        tool_words[n[0] - 'A'] = w.value;
        tool_given = true;
        axis = true;
      } else if (n == "I" || n == "J" || n == "K") {
        centre_offset[n[0] - 'I'] = w.value * unit;
        has_ij = true;
      } else if (n == "R") {
        has_r = true;
      } else if (n == "F") {
        WAAM_THROW_UNLESS(w.value > 0.0, file << ":" << line << ": F" << w.value << " must be > 0");
        feed_mm_s = w.value * unit * feed_scale;
        raw_feed = w.value;
      } else if (n == "E") {
        has_e = true;
        e = w.value;
      } else if (n == "N" || n == "S" || n == "T" || n == "P" || n == "H" || n == "D") {
        // line number, power, tool, dwell, offsets: nothing the path depends on
      } else {
        warnings.Add("word " + n + " not executed", line);
      }
    }
    if (!axis) {
      if (has_e) last_e = e_relative ? last_e : e;
      continue;
    }
    if (tool_given) {
      WAAM_THROW_UNLESS(tool_words.norm() > 1e-9, file << ":" << line << ": tool direction A3 B3 C3 of length 0");
      tool_words.normalize();
    }
    internal::CheckMotionCount(program.motions.size(), file, line);
    const bool extruding = has_e && (e_relative ? e > 0.0 : e > last_e);
    if (has_e && !e_relative) last_e = e;
    ProgramMotion m;
    m.line = line;
    m.kind = mode == 0 ? MotionKind::kJoint : (mode == 1 ? MotionKind::kLinear : MotionKind::kCircular);
    m.has_pose = true;
    m.frame = TargetFrame::kPart;
    m.X_UT.translation() = target;
    m.X_UT.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), -tool_words).toRotationMatrix();
    m.has_positioner = true;
    m.tilt_rad = tilt * kPi / 180.0;
    m.rotation_rad = rotation * kPi / 180.0;
    m.speed_mm_s = mode == 0 ? 0.0 : feed_mm_s;
    m.weld = mode != 0 && (arc_on || extruding);
    if (m.weld && raw_feed > 0.0) weld_feeds.push_back(raw_feed);
    if (m.kind == MotionKind::kCircular) {
      if (!has_ij || has_r || !any_position) {
        warnings.Add(has_r ? "G2/G3 with a radius R: followed as a linear move"
                           : "G2/G3 without I J centre offsets: followed as a linear move",
                     line);
        m.kind = MotionKind::kLinear;
      } else {
        // The arc in the XY plane about pos + (I, J), clockwise for G2; z runs linearly.
        const Eigen::Vector2d c = pos.head<2>() + centre_offset.head<2>();
        const double r = (pos.head<2>() - c).norm();
        WAAM_THROW_UNLESS(r > 1e-9, file << ":" << line << ": G" << mode << " arc of radius 0");
        const double a0 = std::atan2(pos.y() - c.y(), pos.x() - c.x());
        double a1 = std::atan2(target.y() - c.y(), target.x() - c.x());
        double sweep = a1 - a0;
        if (mode == 2) {
          while (sweep >= -1e-12) sweep -= 2.0 * kPi;
        } else {
          while (sweep <= 1e-12) sweep += 2.0 * kPi;
        }
        auto on_arc = [&](double f) {
          const double a = a0 + f * sweep;
          return Eigen::Vector3d(c.x() + r * std::cos(a), c.y() + r * std::sin(a), pos.z() + f * (target.z() - pos.z()));
        };
        if (std::abs(std::abs(sweep) - 2.0 * kPi) < 1e-9) {
          // A full circle: two half circles, so each has three distinct points.
          ProgramMotion half = m;
          half.X_UT.translation() = on_arc(0.5);
          half.has_via = true;
          half.via = on_arc(0.25);
          program.motions.push_back(half);
          m.has_via = true;
          m.via = on_arc(0.75);
        } else {
          m.has_via = true;
          m.via = on_arc(0.5);
        }
      }
    }
    program.motions.push_back(m);
    pos = target;
    tilt_deg = tilt;
    rotation_deg = rotation;
    tool = tool_words;
    any_position = true;
  }
  CheckGcodeFeedUnit(weld_feeds, options.feed_unit, &warnings);
  program.warnings = warnings.Take();
  return program;
}

}  // namespace waam::planner
