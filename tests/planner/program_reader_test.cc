// Tests of the program readers on programs written as controllers and tools write them (tests/data/programs), the
// warnings for what the twin does not execute, circular moves, and every bad input's message.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/numbers.h"
#include "planner/program/program_plan.h"
#include "planner/program/program_reader.h"
#include "planner/program/robot_program.h"
#include "tests/planner/program_files.h"

namespace waam::planner {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::ReadProgramFile;

fs::path Fixture(const char* name) { return fs::path(WAAM_SOURCE_DIR) / "tests" / "data" / "programs" / name; }

// wall.ls is taught in UF 1, which sits on the FANUC world frame.
ProgramFrames WallLsFrames() {
  ProgramFrames frames;
  frames.uframe[1] = {0, 0, 0, 0, 0, 0};
  return frames;
}

ParsedProgram ReadWallLs() { return ReadProgramFile(Fixture("wall.ls"), std::nullopt, {}, {}, WallLsFrames()); }

std::vector<PathPoint> WeldPoints(const ImportedPlan& imported) {
  std::vector<PathPoint> out;
  for (const LayerPath& layer : imported.plan.layers) {
    for (const PathPoint& p : layer.points) {
      if (p.weld) out.push_back(p);
    }
  }
  return out;
}

TEST(ProgramReaderTest, FanucLsWallIsReadWithItsWarnings) {
  const ParsedProgram program = ReadWallLs();
  EXPECT_EQ(program.format, ProgramFormat::kFanucLs);
  EXPECT_EQ(program.name, "WALL");
  ASSERT_EQ(program.motions.size(), 9u);
  EXPECT_EQ(program.MotionsByKind().at("circular"), 1u);
  EXPECT_EQ(program.MotionsByKind().at("joint"), 2u);
  // Weld: the move onto P[2] carries Arc Start (arc off on the way), P[3], P[4] weld; C and P[8] weld (Arc End).
  const std::vector<bool> weld = {false, false, true, true, false, true, true, false, false};
  for (std::size_t i = 0; i < weld.size(); ++i) EXPECT_EQ(program.motions[i].weld, weld[i]) << "motion " << i;
  EXPECT_TRUE(program.motions[8].has_joints);
  EXPECT_NEAR(program.motions[8].q[4], -80.0 * kPi / 180.0, 1e-12);
  EXPECT_NEAR(program.motions[2].speed_mm_s, 400.0 / 60.0, 1e-12) << "40cm/min";
  EXPECT_EQ(program.motions[5].speed_mm_s, 0.0) << "R[5]mm/sec: a register, the scenario's speed";
  const ProgramWarning* call = testing::FindProgramWarning(program, "CALL");
  ASSERT_NE(call, nullptr);
  EXPECT_EQ(call->count, 1);
  EXPECT_EQ(call->first_line, 27);
  const ProgramWarning* weave = testing::FindProgramWarning(program, "WEAVE");
  ASSERT_NE(weave, nullptr);
  EXPECT_EQ(weave->count, 2);
  EXPECT_NE(testing::FindProgramWarning(program, "OFFSET"), nullptr);
  EXPECT_NE(testing::FindProgramWarning(program, "IF"), nullptr);
  EXPECT_NE(testing::FindProgramWarning(program, "register"), nullptr);
}

TEST(ProgramReaderTest, CircularMovesAreCutIntoChordsOnTheCircle) {
  const ParsedProgram program = ReadWallLs();
  ImportSettings settings;
  settings.arc_step_mm = 1.0;
  const CellKinematics cell = testing::ProgramTestCell();
  const ImportedPlan imported = ProgramToPlan(program, cell, settings);
  EXPECT_GT(imported.points, program.motions.size() + 20) << "a 30 mm arc at 1 mm chords";
  // The circle through P[5], P[6], P[7] (user frame): every arc point lies on it, in the plane z = 153.
  const Eigen::Vector3d a(1060, 0, 153), b(1045, 5, 153), c(1030, 0, 153);
  const Eigen::Vector3d u = b - a, v = c - a, w = u.cross(v);
  const Eigen::Vector3d centre = a + (u.squaredNorm() * v - v.squaredNorm() * u).cross(w) / (2.0 * w.squaredNorm());
  const double r = (a - centre).norm();
  const std::vector<ResolvedTarget> targets = ResolveTargets(program, cell, settings);
  const Eigen::Isometry3d X_UP = ProgramUserFrame(cell).inverse() * cell.X_WB *
                                 PartPose(cell.positioner, targets[5].tilt_rad, targets[5].rotation_rad);
  int on_arc = 0;
  for (const LayerPath& layer : imported.plan.layers) {
    for (const PathPoint& p : layer.points) {
      const Eigen::Vector3d p_U = X_UP * p.p_P;
      if (std::abs(p_U.z() - 153.0) > 1e-6 || p_U.x() < 1030.0 - 1e-6 || p_U.x() > 1060.0 + 1e-6 || p_U.y() < 1e-3) {
        continue;
      }
      EXPECT_NEAR((p_U - centre).norm(), r, 1e-6);
      ++on_arc;
    }
  }
  EXPECT_GE(on_arc, 20);
  EXPECT_EQ(imported.plan.layers.size(), 2u) << "passes at z 151.5 and 153 are two layers";
}

TEST(ProgramReaderTest, RapidWallWeldsTheSamePathAsTheFanucWall) {
  const ParsedProgram ls = ReadWallLs();
  const ParsedProgram mod = ReadProgramFile(Fixture("wall.mod"), std::nullopt);
  EXPECT_EQ(mod.format, ProgramFormat::kAbbRapid);
  EXPECT_EQ(mod.name, "WALL");
  EXPECT_EQ(mod.motions.size(), ls.motions.size()) << "Offs(pEnd2, 0, 0, 40) is followed";
  EXPECT_EQ(testing::FindProgramWarning(mod, "TORCHCLEAN"), nullptr) << "main calls TorchClean, a PROC of the module";
  EXPECT_NE(testing::FindProgramWarning(mod, "\\WEAVE"), nullptr);
  // WaitTime 1 after the retract Offs(pEnd2, 0, 0, 40); TorchClean's WaitTime 0.5 runs before the first motion.
  EXPECT_EQ(testing::FindProgramWarning(mod, "WAITTIME"), nullptr);
  EXPECT_NE(testing::FindProgramWarning(mod, "wait before the first motion"), nullptr);
  EXPECT_NEAR(mod.motions[mod.motions.size() - 2].dwell_s, 1.0, 1e-12);
  EXPECT_NEAR(mod.motions.back().dwell_s, 0.0, 1e-12);
  // The program's tool: tWeldGun, 400 mm out of the flange.
  ASSERT_TRUE(mod.motions[0].has_tool);
  EXPECT_EQ(mod.motions[0].tool_name, "tWeldGun");
  EXPECT_LT((mod.motions[0].X_FT.translation() - Eigen::Vector3d(400, 0, 0)).norm(), 1e-9) << "400 mm along the "
                                                                                          "flange normal";
  const CellKinematics cell = testing::ProgramTestCell();
  const std::vector<PathPoint> a = WeldPoints(ProgramToPlan(ls, cell, ImportSettings{}));
  const std::vector<PathPoint> b = WeldPoints(ProgramToPlan(mod, cell, ImportSettings{}));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_LT((a[i].p_P - b[i].p_P).norm(), 1e-6) << "weld point " << i;
    EXPECT_LT((a[i].tool_dir_P - b[i].tool_dir_P).norm(), 1e-9) << "weld point " << i;
  }
}

TEST(ProgramReaderTest, KrlWallWeldsTheSamePathAsTheFanucWall) {
  // wall.src with its wall.dat found beside it; ArcTech ARC_ON / ARC_OFF and $OUT[1] switch the arc.
  const ParsedProgram ls = ReadWallLs();
  const ParsedProgram krl = ReadProgramFile(Fixture("wall.src"), std::nullopt);
  EXPECT_EQ(krl.format, ProgramFormat::kKukaKrl);
  EXPECT_EQ(krl.motions.size(), ls.motions.size());
  // WAIT SEC 1.0 (line 30): the torch waits at XP8, the end of the second layer.
  EXPECT_EQ(testing::FindProgramWarning(krl, "WAIT"), nullptr);
  ASSERT_EQ(krl.motions.size(), 9u);
  EXPECT_EQ(krl.motions[6].line, 28);
  EXPECT_NEAR(krl.motions[6].dwell_s, 1.0, 1e-12);
  const CellKinematics cell = testing::ProgramTestCell();
  const std::vector<PathPoint> a = WeldPoints(ProgramToPlan(ls, cell, ImportSettings{}));
  const std::vector<PathPoint> b = WeldPoints(ProgramToPlan(krl, cell, ImportSettings{}));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_LT((a[i].p_P - b[i].p_P).norm(), 1e-6) << "weld point " << i;
    EXPECT_NEAR(a[i].speed_mm_s, b[i].speed_mm_s, 1e-3) << "weld point " << i;
  }
}

JbiReadOptions WallJbiPulses() {
  JbiReadOptions jbi;
  jbi.robot_pulses_per_deg = {1000.0, 1400.0, 1000.0, 800.0, 1200.0, 500.0};  // as wall_jbi.yaml gives them
  return jbi;
}

// wall.JBI's ///USER 1, as wall_jbi.yaml gives it: the robot frame lifted to the L axis (the FANUC world frame of
// the wall.ls it matches).
ProgramFrames WallJbiFrames() {
  ProgramFrames frames;
  frames.uframe[1] = {0.0, 0.0, 450.0, 0.0, 0.0, 0.0};
  return frames;
}

TEST(ProgramReaderTest, JbiWallWeldsTheSamePathAsTheFanucWall) {
  // ///POSTYPE USER positions in the scenario's user frame; the MOVC circle's first point is where the robot stands;
  // the pulse position C00009 through forward kinematics.
  const ParsedProgram ls = ReadWallLs();
  const ParsedProgram jbi = ReadProgramFile(Fixture("wall.JBI"), std::nullopt, GcodeReadOptions{}, WallJbiPulses(),
                                               WallJbiFrames());
  EXPECT_EQ(jbi.format, ProgramFormat::kYaskawaJbi);
  EXPECT_EQ(jbi.name, "WALL");
  ASSERT_EQ(jbi.motions.size(), ls.motions.size());
  EXPECT_EQ(jbi.MotionsByKind(), ls.MotionsByKind());
  for (std::size_t i = 0; i < ls.motions.size(); ++i) {
    EXPECT_EQ(jbi.motions[i].weld, ls.motions[i].weld) << "motion " << i;
    EXPECT_EQ(jbi.motions[i].has_joints, ls.motions[i].has_joints) << "motion " << i;
  }
  EXPECT_LT((jbi.motions.back().q - ls.motions.back().q).norm(), 1e-12);
  EXPECT_EQ(jbi.motions[1].config, 0);  // ///RCONF 1,0,0: no flip, upper arm, front
  double timer = 0.0;
  for (const ProgramMotion& m : jbi.motions) timer += m.dwell_s;
  EXPECT_NEAR(timer, 0.3 + 1.0, 1e-12) << "ARCON T=0.30 (the time at the start point), TIMER T=1.00";
  for (const char* what : {"CALL", "WVON", "WVOF", "JUMP"}) {
    EXPECT_NE(testing::FindProgramWarning(jbi, what), nullptr) << what;
  }
  EXPECT_EQ(testing::FindProgramWarning(jbi, "CALL")->first_line, 29);
  const CellKinematics cell = testing::ProgramTestCell();
  const std::vector<PathPoint> a = WeldPoints(ProgramToPlan(ls, cell, ImportSettings{}));
  const std::vector<PathPoint> b = WeldPoints(ProgramToPlan(jbi, cell, ImportSettings{}));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_LT((a[i].p_P - b[i].p_P).norm(), 1e-6) << "weld point " << i;
    EXPECT_LT((a[i].tool_dir_P - b[i].tool_dir_P).norm(), 1e-9) << "weld point " << i;
    EXPECT_NEAR(b[i].speed_mm_s, 6.7, 1e-9) << "weld point " << i;
  }
}

TEST(ProgramReaderTest, GcodeWallHasItsArcAndWeldsBetweenTheMCodes) {
  const ParsedProgram program = ReadProgramFile(Fixture("wall.nc"), std::nullopt);
  EXPECT_EQ(program.format, ProgramFormat::kGcode);
  EXPECT_EQ(program.MotionsByKind().at("circular"), 2u) << "the G3 of about 143 degrees, in two pieces of at most 90";
  // N140 G4 P1: one millisecond at the end of the second layer (N120 G1 X-30), in the plan too.
  EXPECT_EQ(testing::FindProgramWarning(program, "G4"), nullptr);
  double dwell = 0.0;
  for (const ProgramMotion& m : program.motions) dwell += m.dwell_s;
  EXPECT_NEAR(dwell, 0.001, 1e-12);
  const ImportedPlan imported = ProgramToPlan(program, testing::ProgramTestCell(), ImportSettings{});
  double plan_dwell = 0.0;
  for (const LayerPath& layer : imported.plan.layers) {
    for (const PathPoint& p : layer.points) plan_dwell += p.dwell_s;
  }
  EXPECT_NEAR(plan_dwell, 0.001, 1e-12);
  EXPECT_EQ(imported.plan.layers.size(), 2u);
  double weld = 0.0;
  for (const LayerPath& layer : imported.plan.layers) {
    for (std::size_t i = 1; i < layer.points.size(); ++i) {
      if (layer.points[i].weld) weld += (layer.points[i].p_P - layer.points[i - 1].p_P).norm();
    }
  }
  // Layer 1: 60 mm straight; layer 2: the G3 arc from (30, 0) to (0, 0) about (15, -5), then 30 mm straight.
  const double r = std::hypot(15.0, 5.0);
  const double arc = r * (kPi - 2.0 * std::atan2(5.0, 15.0));
  EXPECT_NEAR(weld, 60.0 + 30.0 + arc, 0.05);
}

TEST(ProgramReaderTest, CsvTableIsRead) {
  const ParsedProgram program = ReadProgramFile(Fixture("small.csv"), std::nullopt);
  EXPECT_EQ(program.format, ProgramFormat::kCsv);
  EXPECT_EQ(program.motions.size(), 39u);
  EXPECT_TRUE(program.warnings.empty());
}

// Bad inputs: one line naming file:line and what is wrong.
std::string ErrorOf(ProgramFormat format, const std::string& text) {
  try {
    (void)ReadProgramText(text, "bad", format, {}, {}, WallLsFrames());
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string ReplaceOnce(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(ProgramReaderTest, FanucBadInputsNameTheLine) {
  const std::string ls = ReadFile(Fixture("wall.ls"));
  // Truncated /POS: the file ends inside P[10].
  EXPECT_THAT(ErrorOf(ProgramFormat::kFanucLs, ls.substr(0, ls.find("J4="))),
              HasSubstr("P[10] in /POS is not closed by '};' (truncated /POS)"));
  // A position used and not defined.
  EXPECT_THAT(ErrorOf(ProgramFormat::kFanucLs, ReplaceOnce(ls, "L  P[4] 40cm/min", "L  P[14] 40cm/min")),
              HasSubstr("bad:33: P[14] is used but not defined in /POS"));
  EXPECT_THAT(ErrorOf(ProgramFormat::kFanucLs, ReplaceOnce(ls, "X =  1030.000  mm", "X =  abc  mm")),
              HasSubstr("X 'abc' is not a finite number"));
  EXPECT_THAT(ErrorOf(ProgramFormat::kFanucLs, ReplaceOnce(ls, "/END\n", "")), HasSubstr("no /END"));
  EXPECT_THAT(ErrorOf(ProgramFormat::kFanucLs, ReplaceOnce(ls, "40cm/min CNT100 COORD", "40furlong/min CNT100")),
              HasSubstr("bad:31: motion speed unit 'FURLONG/MIN' unknown"));
  EXPECT_THAT(ErrorOf(ProgramFormat::kFanucLs, "L P[1] 10mm/sec FINE ;\n"), HasSubstr("bad:1: expected /PROG"));
}

TEST(ProgramReaderTest, RapidBadInputsNameTheLine) {
  const std::string mod = ReadFile(Fixture("wall.mod"));
  EXPECT_THAT(ErrorOf(ProgramFormat::kAbbRapid,
                      ReplaceOnce(mod, "pMid1:=[[1030,0,151.5],[0,1,0,0]", "pMid1:=[[1030,0,151.5],[0,0,0,0]")),
              HasSubstr("bad:12: quaternion [0,0,0,0] of length 0"));
  EXPECT_THAT(ErrorOf(ProgramFormat::kAbbRapid, ReplaceOnce(mod, "ArcL pMid1", "ArcL pMid9")),
              HasSubstr("bad:25: pMid9 is used but not declared as a ROBTARGET"));
  EXPECT_THAT(ErrorOf(ProgramFormat::kAbbRapid, ReplaceOnce(mod, "ENDMODULE\n", "")), HasSubstr("no ENDMODULE"));
  EXPECT_THAT(ErrorOf(ProgramFormat::kAbbRapid, ReplaceOnce(mod, "[1060,0,151.5]", "[1060,0]")),
              HasSubstr("position [x,y,z] must be a list of 3 numbers"));
}

TEST(ProgramReaderTest, KrlBadInputsNameTheLine) {
  const std::string src = ReadFile(Fixture("wall.src")), dat = ReadFile(Fixture("wall.dat"));
  auto error = [](const std::string& s, const std::string& d) {
    try {
      (void)ReadKukaKrl(s, d, "bad.src", "bad.dat");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error(ReplaceOnce(src, "LIN XP4", "LIN XP14"), dat),
              HasSubstr("bad.src:21: XP14 is used but not declared in the .dat or the .src"));
  EXPECT_THAT(error(src, ReplaceOnce(dat, "{X 1030.0,Y 0.0", "{X nan,Y 0.0")), HasSubstr("bad.dat:8: X 'nan'"));
  EXPECT_THAT(error(ReplaceOnce(src, "\nEND\n", "\n"), dat), HasSubstr("no END"));
  EXPECT_THAT(error(src, ReplaceOnce(dat, ",Y 0.0,Z 151.5", ",Z 151.5")), HasSubstr("bad.dat:7: position lacks Y"));
}

TEST(ProgramReaderTest, JbiStationAxesArePositionerAnglesThroughTheirPulsesPerDegree) {
  std::string jbi = ReadFile(Fixture("wall.JBI"));
  jbi = ReplaceOnce(jbi, "///NPOS 10,0,0,0,0,0", "///NPOS 10,0,2,0,0,0");
  jbi = ReplaceOnce(jbi, "C00009=0,14000,0,0,-96000,0\n", "C00009=0,14000,0,0,-96000,0\nEC00000=0,0\nEC00001=-45000,90000\n");
  jbi = ReplaceOnce(jbi, "///GROUP1 RB1", "///GROUP1 RB1,ST1");
  jbi = ReplaceOnce(jbi, "MOVL C00001 V=100.0", "MOVL C00001 EC00000 V=100.0");
  jbi = ReplaceOnce(jbi, "MOVL C00004 V=100.0", "MOVL C00004 EC00001 V=100.0");
  JbiReadOptions options = WallJbiPulses();
  options.station_pulses_per_deg = {1500.0, 1000.0};
  const ParsedProgram program = ReadYaskawaJbi(jbi, "wall.JBI", options, WallJbiFrames());
  ASSERT_TRUE(program.motions[1].has_positioner);
  EXPECT_EQ(program.motions[1].tilt_rad, 0.0);
  ASSERT_TRUE(program.motions[4].has_positioner);
  EXPECT_NEAR(program.motions[4].tilt_rad * kDeg, -30.0, 1e-12);
  EXPECT_NEAR(program.motions[4].rotation_rad * kDeg, 90.0, 1e-12);
  // Without the station's pulses per degree the EC position is refused, naming the setting.
  try {
    (void)ReadYaskawaJbi(jbi, "wall.JBI", WallJbiPulses(), WallJbiFrames());
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("wall.JBI:22: station positions are encoder pulses and the station's pulses per "
                                    "degree are unknown: give program.yaskawa.station_pulses_per_deg"));
  }
}

TEST(ProgramReaderTest, JbiBadInputsNameTheLine) {
  const std::string jbi = ReadFile(Fixture("wall.JBI"));
  auto error = [](const std::string& text, const JbiReadOptions& options) {
    try {
      (void)ReadYaskawaJbi(text, "bad.JBI", options, WallJbiFrames());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const JbiReadOptions pulses = WallJbiPulses();
  // A wrong count: NPOS says 3 C positions, 2 are given.
  const std::string three = "/JOB\n//NAME W\n//POS\n///NPOS 3,0,0,0,0,0\n///TOOL 1\n///POSTYPE ROBOT\n///RECTAN\n"
                            "C00000=1000,0,180,180,0,0\nC00001=1000,0,150,180,0,0\n//INST\n///GROUP1 RB1\nNOP\n"
                            "MOVJ C00000 VJ=10.00\nMOVL C00001 V=10.0\nEND\n";
  EXPECT_THAT(error(three, pulses), HasSubstr("bad.JBI:4: ///NPOS says 3 C positions, 2 are given"));
  EXPECT_EQ(error(ReplaceOnce(three, "NPOS 3", "NPOS 2"), pulses), "no error");
  // A MOVL naming a C variable that //POS does not define.
  EXPECT_THAT(error(ReplaceOnce(jbi, "MOVL C00003 V=6.7", "MOVL C00013 V=6.7"), pulses),
              HasSubstr("bad.JBI:36: C00013 is used but not defined in //POS"));
  // A truncated //POS.
  EXPECT_THAT(error(jbi.substr(0, jbi.find("C00006=")), pulses),
              HasSubstr("bad.JBI:15: the job ends inside //POS (no //INST): it is truncated"));
  // A pulse position without the arm's pulses per degree.
  EXPECT_THAT(error(jbi, JbiReadOptions{}),
              HasSubstr("bad.JBI:21: a pulse position and the robot's pulses per degree are unknown (axis S)"));
  EXPECT_THAT(error(ReplaceOnce(jbi, "C00002=1030.000", "C00002=nan"), pulses),
              HasSubstr("bad.JBI:12: C00002 value 'nan' is not a finite number"));
  EXPECT_THAT(error(ReplaceOnce(jbi, "0.000,151.500,180.0000,0.0000,0.0000\nC00003", "0.000,151.500\nC00003"), pulses),
              HasSubstr("bad.JBI:12: C00002 has 3 values; a robot position has six"));
  EXPECT_THAT(error(ReplaceOnce(jbi, "\nEND\n", "\n"), pulses), HasSubstr("no END"));
  EXPECT_THAT(error(ReplaceOnce(jbi, "///POSTYPE USER", "///POSTYPE CYLINDER"), pulses),
              HasSubstr("bad.JBI:7: ///POSTYPE 'CYLINDER': must be ROBOT, BASE, USER or PULSE"));
  EXPECT_THAT(error(ReplaceOnce(jbi, "/JOB\n", ""), pulses), HasSubstr("bad.JBI:1: a JBI job starts with /JOB"));
}

TEST(ProgramReaderTest, GcodeBadInputsNameTheLine) {
  EXPECT_THAT(ErrorOf(ProgramFormat::kGcode, "G21\nG1 X1 Y2 Z3 F400\nG1 XNaN Y2\n"),
              HasSubstr("bad:3: X 'NaN' is not a finite number"));
  EXPECT_THAT(ErrorOf(ProgramFormat::kGcode, "G1 X1.2.3 Y0\n"), HasSubstr("bad:1: X '1.2.3' is not a finite number"));
  EXPECT_THAT(ErrorOf(ProgramFormat::kGcode, "G1 X1 A3=0 B3=0 C3=0\n"),
              HasSubstr("bad:1: tool direction A3 B3 C3 of length 0"));
  EXPECT_THAT(ErrorOf(ProgramFormat::kGcode, "G1 X1 F-5\n"), HasSubstr("bad:1: F-5 must be >= 0"));
  EXPECT_THAT(ErrorOf(ProgramFormat::kGcode, "G1 X1 (open comment\n"), HasSubstr("bad:1: comment '('"));
}

TEST(ProgramReaderTest, UnknownFormatAsksForFormat) {
  EXPECT_THAT([] {
    try {
      (void)DetectProgramFormat("prog.txt", "hello\n");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  }(),
              HasSubstr("give --format"));
}

}  // namespace
}  // namespace waam::planner
