// The G-code reader on the controllers' grammar: words and comments, modes, arcs in the three planes, arc signals of
// the WAAM dialects, units, and a bar-on-plate build whose timeline is its path length over its feed plus its dwells.
#include <cmath>
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/numbers.h"
#include "planner/program/program_plan.h"
#include "planner/program/program_reader.h"
#include "tests/planner/program_files.h"
#include "planner/timeline/timeline.h"

namespace waam::planner {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string GcodeError(const std::string& text, const GcodeReadOptions& options = {}) {
  try {
    (void)ReadGcode(text, "bad.nc", options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

GcodeReadOptions PerSecond() {
  GcodeReadOptions options;
  options.feed_unit = GcodeFeedUnit::kMmPerS;
  return options;
}

TEST(GcodeGrammarTest, BarOnPlateTimelineIsPathOverFeedPlusDwells) {
  const std::string text = ReadFile(fs::path(WAAM_SOURCE_DIR) / "tests/data/programs/bar_on_plate.gcode");
  const ParsedProgram program = ReadGcode(text, "bar_on_plate.gcode", PerSecond());
  EXPECT_EQ(testing::FindProgramWarning(program, "look like"), nullptr) << "F8 read as mm/s";
  ImportSettings import;
  import.bead_height_mm = 1.8;
  const ImportedPlan imported = ProgramToPlan(program, testing::ProgramTestCell(), import);
  ASSERT_EQ(imported.plan.layers.size(), 5u);
  TimelineSettings settings;
  settings.arc_start_s = 0.0;
  settings.arc_end_s = 0.0;
  const Timeline timeline = BuildTimeline(imported.plan, {}, AxisLimits{}, settings);
  ASSERT_EQ(timeline.layers.size(), 5u);
  double waits = 0.0;
  for (const LayerTimes& layer : timeline.layers) {
    // Each layer: one 120 mm pass at F8 (mm/s).
    EXPECT_NEAR(layer.arc_on_s, 120.0 / 8.0, 1e-6) << "layer " << layer.layer;
    EXPECT_NEAR(layer.end_s - layer.start_s, 120.0 / 8.0, 1e-6) << "layer " << layer.layer;
    waits += layer.wait_s;
  }
  // Four dwells of 60 s: G4 S60 three times and G4 P60000 (ms) once.
  EXPECT_NEAR(waits, 4 * 60.0, 1e-9);
  EXPECT_NEAR(timeline.wait_s, 4 * 60.0, 1e-9);
  for (int l = 1; l < 5; ++l) {
    EXPECT_GE(timeline.layers[l].start_s - timeline.layers[l - 1].end_s, 60.0)
        << "the dwell lies between layer " << l - 1 << "'s last arc end and layer " << l << "'s first arc start";
  }
  // Read as mm/min the same program welds 60 times slower, and says the feeds look like mm/s.
  const ParsedProgram per_min = ReadGcode(text, "bar_on_plate.gcode");
  EXPECT_NE(testing::FindProgramWarning(per_min, "look like mm/s"), nullptr);
}

GcodeReadOptions Wolf() {
  GcodeReadOptions options = PerSecond();
  options.arc_on = {"M101"};
  options.arc_off = {"M103"};
  options.dwell_p_unit = GcodeDwellUnit::kS;
  return options;
}

TEST(GcodeGrammarTest, OrnlWolfSyntaxRunsWithItsPumpSignalsPackedWordsAndDwells) {
  // tests/data/programs/wolf_bar.gcode: three layers of two 60 mm tracks 4 mm apart at F5 (mm/s), M101 / M103 the
  // arc, G4 S30 and S20 between layers; "BEGINNING LAYER" lines, M5T2D1F0 packed words, M6, T1.
  const std::string text = ReadFile(fs::path(WAAM_SOURCE_DIR) / "tests/data/programs/wolf_bar.gcode");
  const ParsedProgram program = ReadGcode(text, "wolf_bar.gcode", Wolf());
  // What the twin does not run is listed with its count and first line, never dropped.
  const struct {
    const char* what;
    int count, first_line;
  } kWarned[] = {{"statement BEGINNING", 3, 5}, {"F0 programs no feed", 3, 7}, {"M5 not executed", 3, 7},
                 {"M6 not executed", 3, 16},    {"T1 tool select", 1, 6},      {"T2 tool select", 4, 7}};
  for (const auto& w : kWarned) {
    const ProgramWarning* found = testing::FindProgramWarning(program, w.what);
    ASSERT_NE(found, nullptr) << w.what;
    EXPECT_EQ(found->count, w.count) << w.what;
    EXPECT_EQ(found->first_line, w.first_line) << w.what;
  }
  EXPECT_EQ(testing::FindProgramWarning(program, "look like"), nullptr) << "F5 read as mm/s";
  ImportSettings import;
  import.bead_height_mm = 2.0;
  const ImportedPlan imported = ProgramToPlan(program, testing::ProgramTestCell(), import);
  ASSERT_EQ(imported.plan.layers.size(), 3u);
  TimelineSettings settings;
  settings.arc_start_s = 0.0;
  settings.arc_end_s = 0.0;
  const Timeline timeline = BuildTimeline(imported.plan, {}, AxisLimits{}, settings);
  ASSERT_EQ(timeline.layers.size(), 3u);
  for (const LayerTimes& layer : timeline.layers) {
    // 60 + 4 + 60 mm at 5 mm/s; the F0 before layers 2 and 3 keeps the feed in force (F5), no move runs at zero feed.
    EXPECT_NEAR(layer.arc_on_s, 124.0 / 5.0, 1e-6) << "layer " << layer.layer;
    // The G4 after M103 waits after the pass's arc end: the layer ends at its last arc end, not after the dwell.
    EXPECT_NEAR(layer.end_s - layer.start_s, 124.0 / 5.0, 1e-6) << "layer " << layer.layer;
  }
  EXPECT_NEAR(timeline.wait_s, 30.0 + 20.0, 1e-9);
  EXPECT_GE(timeline.layers[1].start_s - timeline.layers[0].start_s, 124.0 / 5.0 + 30.0);
  EXPECT_GE(timeline.layers[2].start_s - timeline.layers[1].start_s, 124.0 / 5.0 + 20.0);
  // With M3 / M5 as the signals (the default), M101 / M103 are warned and nothing is welded.
  const ParsedProgram plain = ReadGcode(text, "wolf_bar.gcode", PerSecond());
  EXPECT_NE(testing::FindProgramWarning(plain, "M101 not executed"), nullptr);
  for (const ProgramMotion& m : plain.motions) EXPECT_FALSE(m.weld) << "line " << m.line;
}

TEST(GcodeGrammarTest, WordsCommentsLineNumbersAndChecksums) {
  // Compact words, lower case, N numbers, '*' checksums, '( )' and ';' comments, '/' block delete, '%', spaces
  // inside a word, ISG's X= form.
  const std::string text =
      "%\nN10G21G90(mm, absolute)\nn20 g0 x1 y2 z3*57\n/N30 G1 X 4 Y-2.5 F600 ; feed\nG1 X=5 Y=6\nM117 Layer 1 done\n";
  const ParsedProgram p = ReadGcode(text, "compact.nc");
  ASSERT_EQ(p.motions.size(), 3u);
  EXPECT_EQ(p.motions[0].kind, MotionKind::kJoint);
  EXPECT_EQ(p.motions[0].X_UT.translation(), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(p.motions[1].X_UT.translation(), Eigen::Vector3d(4, -2.5, 3));
  EXPECT_NEAR(p.motions[1].speed_mm_s, 10.0, 1e-12);
  EXPECT_EQ(p.motions[1].line, 4);
  EXPECT_EQ(p.motions[2].X_UT.translation(), Eigen::Vector3d(5, 6, 3)) << "ISG's X= and modal G1 and F";
  EXPECT_NEAR(p.motions[2].speed_mm_s, 10.0, 1e-12);
  EXPECT_NE(testing::FindProgramWarning(p, "block delete"), nullptr);
  EXPECT_TRUE(p.warnings.size() == 1u) << p.warnings.size() << " warnings; M117's text is a message";
}

TEST(GcodeGrammarTest, ModesUnitsRelativeAndG92) {
  const std::string text =
      "G20 G90\nG1 X1 Y0 Z0 F10\nG91\nG1 X1\nG90 G21\nG92 X0 Y0 Z0\nG1 X10\nG92.1\nG1 X10\nT1\nT1\nG1 B5 X11\n"
      "M30\nG1 X99\n";
  const ParsedProgram p = ReadGcode(text, "modes.nc");
  ASSERT_EQ(p.motions.size(), 5u);
  EXPECT_NEAR(p.motions[0].X_UT.translation().x(), 25.4, 1e-12) << "G20: inches";
  EXPECT_NEAR(p.motions[0].speed_mm_s, 25.4 * 10.0 / 60.0, 1e-12) << "F in inches per minute";
  EXPECT_NEAR(p.motions[1].X_UT.translation().x(), 50.8, 1e-12) << "G91: one inch on";
  EXPECT_NEAR(p.motions[2].X_UT.translation().x(), 60.8, 1e-12) << "G92 X0 at 50.8 mm: X10 is 60.8 mm";
  EXPECT_NEAR(p.motions[3].X_UT.translation().x(), 10.0, 1e-12) << "G92.1 clears the offset";
  const ProgramWarning* t = testing::FindProgramWarning(p, "T1 tool select");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->count, 2) << "one warning, counted";
  EXPECT_NE(testing::FindProgramWarning(p, "word B not executed"), nullptr);
  EXPECT_NE(testing::FindProgramWarning(p, "after the program's end"), nullptr) << "M30 ends the program";
}

// The centre of the circle through three points (in their plane).
Eigen::Vector3d CircleCentre(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, n = ab.cross(ac);
  return a + (ac.squaredNorm() * n.cross(ab) + ab.squaredNorm() * ac.cross(n)) / (2.0 * n.squaredNorm());
}

TEST(GcodeGrammarTest, ArcsInEachPlaneWithCentresOrRadii) {
  struct Case {
    const char* text;
    Eigen::Vector3d centre;
    double sweep_deg;  // the arc's angle (negative: clockwise)
  };
  const Case cases[] = {
      {"G17 G0 X10 Y0 Z0\nG3 X0 Y10 I-10 J0 F600\n", {0, 0, 0}, 90},          // XY, I J
      {"G17 G0 X10 Y0 Z0\nG2 X0 Y10 I-10 J0 F600\n", {0, 0, 0}, -270},        // the long way round, clockwise
      {"G17 G0 X10 Y0 Z0\nG3 X10 Y0 I-10 J0 F600\n", {0, 0, 0}, 360},         // a full circle
      {"G17 G0 X10 Y0 Z0\nG3 X0 Y10 R10 F600\n", {0, 0, 0}, 90},              // R > 0: the short arc
      {"G17 G0 X10 Y0 Z0\nG3 X0 Y10 R-10 F600\n", {10, 10, 0}, 270},          // R < 0: the long arc
      {"G18 G0 X0 Y0 Z10\nG3 X10 Z0 K-10 I0 F600\n", {0, 0, 0}, 90},          // ZX: K I, about +Y
      {"G19 G0 X0 Y10 Z0\nG3 Y0 Z10 J-10 K0 F600\n", {0, 0, 0}, 90},          // YZ: J K, about +X
      {"G90.1 G17 G0 X10 Y0 Z0\nG3 X0 Y10 I0 J0 F600\n", {0, 0, 0}, 90},     // absolute centre
  };
  for (const Case& c : cases) {
    const ParsedProgram p = ReadGcode(c.text, "arc.nc");
    ASSERT_GE(p.motions.size(), 2u) << c.text;
    const int pieces = static_cast<int>(std::ceil(std::abs(c.sweep_deg) / 90.0 - 1e-9));
    ASSERT_EQ(p.motions.size(), 1u + pieces) << c.text;
    Eigen::Vector3d from = p.motions[0].X_UT.translation();
    const double r = (from - c.centre).norm();
    double swept = 0.0;
    for (std::size_t k = 1; k < p.motions.size(); ++k) {
      const ProgramMotion& m = p.motions[k];
      ASSERT_EQ(m.kind, MotionKind::kCircular);
      ASSERT_TRUE(m.has_via);
      const Eigen::Vector3d to = m.X_UT.translation();
      EXPECT_LT((CircleCentre(from, m.via, to) - c.centre).norm(), 1e-9) << c.text;
      EXPECT_NEAR((m.via - c.centre).norm(), r, 1e-9) << c.text;
      const Eigen::Vector3d n = (from - c.centre).cross(to - c.centre);
      swept += std::atan2(n.norm(), (from - c.centre).dot(to - c.centre)) * kDeg;  // each piece is at most 90 deg
      from = to;
    }
    EXPECT_NEAR(std::abs(swept), std::abs(c.sweep_deg), 1e-6) << c.text;
  }
  // A helix: the normal axis runs linearly along the sweep.
  const ParsedProgram helix = ReadGcode("G0 X10 Y0 Z0\nG3 X10 Y0 Z4 I-10 J0 F600\n", "helix.nc");
  ASSERT_EQ(helix.motions.size(), 5u);
  for (int k = 1; k <= 4; ++k) EXPECT_NEAR(helix.motions[k].X_UT.translation().z(), k, 1e-12);
  EXPECT_NEAR(helix.motions[1].via.z(), 0.5, 1e-12);
}

TEST(GcodeGrammarTest, ArcSignalsOfTheWaamDialects) {
  struct Dialect {
    std::vector<std::string> on, off;
    const char* text;
  };
  const Dialect dialects[] = {
      {{"M3"}, {"M5"}, "G0 X0 Y0 Z1\nM3 S200\nG1 X10 F300\nM5\nG0 Z10\n"},
      {{"M101"}, {"M103"}, "G0 X0 Y0 Z1\nM101\nG1 X10 F300\nM103\nG0 Z10\n"},
      {{"M7", "M8"}, {"M9"}, "G0 X0 Y0 Z1\nM8\nG1 X10 F300\nM9\nG0 Z10\n"},
      {{"G82"}, {"G83"}, "G0 X0 Y0 Z1\nG82\nG1 X10 F300\nG83\nG0 Z10\n"},
      {{"M62 P1"}, {"M63 P1"}, "G0 X0 Y0 Z1\nM62 P2\nM62 P1\nG1 X10 F300\nM63 P1\nG0 Z10\n"},
      {{"M106"}, {"M107"}, "G0 X0 Y0 Z1\nM106 S255\nG1 X10 F300\nM107\nG0 Z10\n"},
      {{"M42 P2 S1"}, {"M42 P2 S0"}, "G0 X0 Y0 Z1\nM42 P2 S1\nG1 X10 F300\nM42 P2 S0\nG0 Z10\n"},
  };
  for (const Dialect& d : dialects) {
    GcodeReadOptions options;
    options.arc_on = d.on;
    options.arc_off = d.off;
    const ParsedProgram p = ReadGcode(d.text, "signals.nc", options);
    ASSERT_EQ(p.motions.size(), 3u) << d.text;
    EXPECT_FALSE(p.motions[0].weld) << d.text;
    EXPECT_TRUE(p.motions[1].weld) << d.text;
    EXPECT_FALSE(p.motions[2].weld) << d.text;
    EXPECT_EQ(testing::FindProgramWarning(p, d.on[0].substr(0, d.on[0].find(' ')) + " not executed"), nullptr) << d.text;
  }
  // M62 P2 is another output: warned, the arc stays off.
  GcodeReadOptions m62;
  m62.arc_on = {"M62 P1"};
  m62.arc_off = {"M63 P1"};
  EXPECT_FALSE(ReadGcode("G0 X0\nM62 P2\nG1 X5 F60\n", "a.nc", m62).motions[1].weld);
  // An extruder's growing E welds (Marlin-style WAAM: the wire feed is the E axis), relative with M83; G92 E0 resets.
  const ParsedProgram e =
      ReadGcode("G0 X0 Y0 Z1\nG92 E0\nG1 X10 E5 F300\nG1 X20 E5\nG92 E0\nG1 X30 E1\nM83\nG1 X40 E1\nG1 X50 E-1\n", "e.nc");
  ASSERT_EQ(e.motions.size(), 6u);
  EXPECT_TRUE(e.motions[1].weld);
  EXPECT_FALSE(e.motions[2].weld) << "E stays at 5";
  EXPECT_TRUE(e.motions[3].weld) << "E1 after G92 E0";
  EXPECT_TRUE(e.motions[4].weld) << "M83: E1 extrudes";
  EXPECT_FALSE(e.motions[5].weld) << "M83: E-1 retracts";
}

TEST(GcodeGrammarTest, DwellUnitsAndStatementsTheTwinDoesNotRun) {
  const std::string text = "G0 X0 Y0 Z1\nG4 P30\nG4 X1.5\nG4 F2\n#TRAFO ON\nTRAORI\nO100 SUB\nG1 X1 F60\n";
  const ParsedProgram ms = ReadGcode(text, "dwell.nc");
  EXPECT_NEAR(ms.motions[0].dwell_s, 0.03 + 1.5 + 2.0, 1e-12) << "P ms, FANUC X s, Sinumerik F s";
  EXPECT_NE(testing::FindProgramWarning(ms, "dwell_p_unit: s"), nullptr) << "P30 as 30 ms looks like seconds";
  for (const char* what : {"statement #TRAFO", "statement TRAORI", "statement O"}) {
    EXPECT_NE(testing::FindProgramWarning(ms, what), nullptr) << what;
  }
  GcodeReadOptions seconds;
  seconds.dwell_p_unit = GcodeDwellUnit::kS;
  const ParsedProgram s = ReadGcode(text, "dwell.nc", seconds);
  EXPECT_NEAR(s.motions[0].dwell_s, 30.0 + 1.5 + 2.0, 1e-12);
  EXPECT_EQ(testing::FindProgramWarning(s, "dwell_p_unit"), nullptr);
}

TEST(GcodeGrammarTest, WhatTheControllerRefusesIsRefusedOnOneLine) {
  EXPECT_THAT(GcodeError("G0 X0 Y0\nG2 X10 Y0 F60\n"), HasSubstr("bad.nc:2: G2 needs its centre (I J) or a radius R"));
  EXPECT_THAT(GcodeError("G0 X0 Y0\nG2 X10 Y0 R2 F60\n"),
              HasSubstr("bad.nc:2: G2 R2 is shorter than half the distance to the end point"));
  EXPECT_THAT(GcodeError("G0 X0 Y0\nG3 X0 Y0 R5 F60\n"), HasSubstr("bad.nc:2: G3 with R from its start to the same point"));
  EXPECT_THAT(GcodeError("G0 X0 Y0\nG3 X10 Y1 I5 J0 F60\n"), HasSubstr("bad.nc:2: G3: the end point is"));
  EXPECT_THAT(GcodeError("G0 X0\nG4 P10 Y5\n"), HasSubstr("bad.nc:2: G4 with the axis word Y: a dwell moves no axis"));
  EXPECT_THAT(GcodeError("G0 X0\nG1 X#1 F60\n"), HasSubstr("bad.nc:2: X '#1' is not a finite number"));
  EXPECT_THAT(GcodeError("G0 X0\nG1 X1 F60 $\n"), HasSubstr("bad.nc:2: unexpected '$'"));
  EXPECT_THAT(GcodeError("M5T2D1F-1\nG1 X1\n"), HasSubstr("bad.nc:1: F-1 must be >= 0"));
  GcodeReadOptions bad;
  bad.arc_on = {"X3"};
  EXPECT_THAT(GcodeError("G0 X0\n", bad), HasSubstr("program.gcode.arc_on 'X3': an arc signal is a G or M code"));
}

}  // namespace
}  // namespace waam::planner
