// The program readers on their dialects' documented grammar: FANUC ArcTool statements without line numbers and
// weld-schedule speeds, KUKA programs that set their own base and tool, waits, G-code feeds in mm/s.
#include <cmath>
#include <filesystem>
#include <functional>

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

fs::path GrammarFixture(const char* name) { return fs::path(WAAM_SOURCE_DIR) / "tests" / "data" / "programs" / name; }

std::string GrammarReplace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string GrammarError(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// arctool_bead.ls: UF 6 and UT 5, which the scenario gives.
ProgramFrames ArcToolFrames() {
  ProgramFrames frames;
  frames.uframe[6] = {500.0, -50.0, 200.0, 0.0, 0.0, 90.0};  // x y z w p r: turned 90 deg about z
  frames.utool[5] = {0.0, 0.0, 420.0, 0.0, -25.0, 0.0};
  return frames;
}

TEST(ProgramGrammarTest, FanucArcToolExportWithWeldScheduleSpeedsAndUnnumberedStatements) {
  const fs::path file = GrammarFixture("arctool_bead.ls");
  EXPECT_THAT(GrammarError([&] { (void)ReadProgramFile(file, std::nullopt); }),
              HasSubstr("arctool_bead.ls:26: P[1] is taught in user frame UF 6, which the program does not define: "
                        "give program.frames.uframe.6"));
  ProgramFrames no_tool = ArcToolFrames();
  no_tool.utool = {{1, std::nullopt}};
  EXPECT_THAT(GrammarError([&] { (void)ReadProgramFile(file, std::nullopt, {}, {}, no_tool); }),
              HasSubstr("P[1] is taught with tool UT 5, which the program does not define"));

  const ParsedProgram program = ReadProgramFile(file, std::nullopt, {}, {}, ArcToolFrames());
  EXPECT_EQ(program.name, "ARCTOOL_BEAD");
  // J P1, L P2..P4, L P5 (unnumbered, FINE on the next line; the //L line is disabled), L P6, C P7 P8, L P9, J P10.
  ASSERT_EQ(program.motions.size(), 9u);
  const std::vector<bool> weld = {false, false, true, true, false, false, true, true, false};
  for (std::size_t i = 0; i < weld.size(); ++i) EXPECT_EQ(program.motions[i].weld, weld[i]) << "motion " << i;
  EXPECT_EQ(program.motions[4].line, 35) << "the unnumbered L P[5] starts on line 35";
  EXPECT_NEAR(program.motions[4].speed_mm_s, 100.0, 1e-12);
  EXPECT_EQ(program.motions[2].speed_mm_s, 0.0) << "WELD_SPEED: the weld schedule's, not in the program";
  EXPECT_NEAR(program.motions[6].speed_mm_s, 12.0, 1e-12);
  EXPECT_EQ(program.motions[6].kind, MotionKind::kCircular);
  const ProgramWarning* schedule = testing::FindProgramWarning(program, "WELD_SPEED");
  ASSERT_NE(schedule, nullptr);
  EXPECT_EQ(schedule->count, 4);
  ASSERT_NE(testing::FindProgramWarning(program, "WEAVE"), nullptr);
  EXPECT_EQ(testing::FindProgramWarning(program, "WEAVE")->count, 2);
  EXPECT_NE(testing::FindProgramWarning(program, "R[4]"), nullptr);
  // WAIT 45.00(sec) after the bead's end P[4]; WAIT 1.50(sec) after P[9].
  EXPECT_NEAR(program.motions[3].dwell_s, 45.0, 1e-12);
  EXPECT_NEAR(program.motions[7].dwell_s, 1.5, 1e-12);
  // P[3] (60, 0, 10) in UF 6: turned 90 deg about z and moved to (500, -50, 200) in the FANUC world frame.
  const ProgramMotion& p3 = program.motions[2];
  EXPECT_EQ(p3.frame, TargetFrame::kArmWorld);
  EXPECT_LT((p3.X_UT.translation() - Eigen::Vector3d(500.0, 10.0, 210.0)).norm(), 1e-9);
  EXPECT_TRUE(p3.has_tool);
  EXPECT_EQ(p3.tool_name, "UT 5");
  EXPECT_LT((p3.X_FT.translation() - Eigen::Vector3d(0.0, 0.0, 420.0)).norm(), 1e-9);

  // The plan: the weld schedule's speed is the scenario's, the waits are on the points, the tool is UT 5.
  ImportSettings settings;
  settings.weld_speed_mm_s = 5.0;
  const ImportedPlan imported = ProgramToPlan(program, testing::ProgramTestCell(), settings);
  ASSERT_TRUE(imported.plan.X_FT.has_value());
  EXPECT_EQ(imported.plan.tool_name, "UT 5");
  double dwell = 0.0;
  for (const LayerPath& layer : imported.plan.layers) {
    for (const PathPoint& p : layer.points) {
      dwell += p.dwell_s;
      if (p.weld) {
        EXPECT_TRUE(p.speed_mm_s == 5.0 || p.speed_mm_s == 12.0) << p.speed_mm_s;
      }
    }
  }
  EXPECT_NEAR(dwell, 46.5, 1e-12);
}

TEST(ProgramGrammarTest, FanucStatementsWithAndWithoutLineNumbersReadTheSame) {
  const std::string pos =
      "/POS\nP[1]{\n   GP1:\n\tUF : 0, UT : 1,\n\tX = 1000.0 mm, Y = 0.0 mm, Z = 180.0 mm,\n"
      "\tW = 180.0 deg, P = 0.0 deg, R = 0.0 deg\n};\n/END\n";
  const std::string numbered = "/PROG T\n/MN\n   1:  UFRAME_NUM=0 ;\n   2:L P[1] 100mm/sec FINE ;\n" + pos;
  const std::string bare = "/PROG T\n/MN\nUFRAME_NUM=0 ;\nL P[1]\n  100mm/sec\n  FINE ;\n" + pos;
  const ParsedProgram a = ReadFanucLs(numbered, "a.ls");
  const ParsedProgram b = ReadFanucLs(bare, "b.ls");
  ASSERT_EQ(a.motions.size(), 1u);
  ASSERT_EQ(b.motions.size(), 1u);
  EXPECT_TRUE(a.motions[0].X_UT.isApprox(b.motions[0].X_UT));
  EXPECT_EQ(a.motions[0].speed_mm_s, b.motions[0].speed_mm_s);
  // What the controller refuses: a UF other than the UFRAME_NUM in force; a motion without its termination.
  EXPECT_THAT(GrammarError([&] { (void)ReadFanucLs(GrammarReplace(numbered, "UFRAME_NUM=0", "UFRAME_NUM=2"), "c.ls"); }),
              HasSubstr("c.ls:4: P[1] is taught in UF 0 but UFRAME_NUM is 2"));
  EXPECT_THAT(GrammarError([&] { (void)ReadFanucLs(GrammarReplace(numbered, "100mm/sec FINE", "100mm/sec"), "d.ls"); }),
              HasSubstr("d.ls:4: motion without its termination"));
}

// base_tool.src sets BASE_DATA[8] and TOOL_DATA[4] itself and moves in them (inline forms with FDAT_ACT and BAS).
TEST(ProgramGrammarTest, KrlPositionsAreTakenInTheBaseAndToolTheProgramSets) {
  const ParsedProgram program = ReadProgramFile(GrammarFixture("base_tool.src"), std::nullopt);
  ASSERT_EQ(program.motions.size(), 5u);  // PTP XHOME, LIN XP1..XP4
  const Eigen::Isometry3d X_RB = internal::PoseXyzAbc(900.0, -100.0, 400.0, 90.0, 0.0, 0.0);
  const Eigen::Isometry3d X_FT = internal::PoseXyzAbc(10.0, 0.0, 380.0, 0.0, -20.0, 0.0);
  const Eigen::Isometry3d X_BP1 = internal::PoseXyzAbc(20.0, 0.0, 40.0, 0.0, 0.0, 180.0);
  const ProgramMotion& p1 = program.motions[1];
  EXPECT_EQ(p1.frame, TargetFrame::kRobot);
  EXPECT_TRUE(p1.X_UT.isApprox(X_RB * X_BP1, 1e-12));
  EXPECT_TRUE(p1.has_tool);
  EXPECT_EQ(p1.tool_name, "TOOL_DATA[4]");
  EXPECT_TRUE(p1.X_FT.isApprox(X_FT, 1e-12));
  EXPECT_NEAR(program.motions[2].speed_mm_s, 8.0, 1e-9) << "BAS(#CP_PARAMS,0.008): m/s";
  EXPECT_TRUE(program.motions[2].weld);
  EXPECT_NEAR(program.motions[3].dwell_s, 30.0, 1e-12) << "WAIT SEC 30.0 after XP3";
  EXPECT_NE(testing::FindProgramWarning(program, "INTERRUPT"), nullptr);

  // The check moves TOOL_DATA[4]; the home position (joints, FDAT tool 0) is found again with it.
  const CellKinematics cell = testing::ProgramTestCell();
  const ImportedPlan imported = ProgramToPlan(program, cell, ImportSettings{});
  ASSERT_TRUE(imported.plan.X_FT.has_value());
  EXPECT_TRUE(imported.plan.X_FT->isApprox(X_FT, 1e-12));
  const std::vector<ResolvedTarget> targets = ResolveTargets(program, cell, ImportSettings{});
  EXPECT_TRUE(targets[1].X_WT.isApprox(cell.X_WR * X_RB * X_BP1, 1e-9));
  const Joints6 q_home = program.motions[0].q;
  EXPECT_TRUE(targets[0].X_WT.isApprox(cell.X_WR * ForwardKinematics(cell.arm, q_home) * X_FT, 1e-9));

  // BASE_DATA[8] kept on the controller: refused without program.frames.uframe.8, the same targets with it.
  const std::string src = ReadFile(GrammarFixture("base_tool.src")), dat = ReadFile(GrammarFixture("base_tool.dat"));
  const std::string kept = GrammarReplace(src, "BASE_DATA[8]={FRAME: X 900.0,Y -100.0,Z 400.0,A 90.0,B 0.0,C 0.0}", "");
  EXPECT_THAT(GrammarError([&] { (void)ReadKukaKrl(kept, dat, "kept.src", "kept.dat"); }),
              HasSubstr("kept.src:31: $BASE is BASE_DATA[8], which the program does not define: give "
                        "program.frames.uframe.8"));
  ProgramFrames frames;
  frames.uframe[8] = {900.0, -100.0, 400.0, 90.0, 0.0, 0.0};
  const ParsedProgram from_scenario = ReadKukaKrl(kept, dat, "kept.src", "kept.dat", frames);
  ASSERT_EQ(from_scenario.motions.size(), program.motions.size());
  for (std::size_t i = 1; i < program.motions.size(); ++i) {
    EXPECT_TRUE(from_scenario.motions[i].X_UT.isApprox(program.motions[i].X_UT, 1e-12)) << "motion " << i;
  }
}

TEST(ProgramGrammarTest, GcodeDwellsAndFeedUnits) {
  const std::string mm_s = "G21\nG0 X0 Y0 Z2\nM3\nG1 X40 F8\nG4 P1500\nG1 X80 F8\nM5\nG4 S12\nG0 Z30\n";
  const ParsedProgram per_min = ReadGcode(mm_s, "bar.nc");
  EXPECT_NEAR(per_min.motions[1].speed_mm_s, 8.0 / 60.0, 1e-12);
  ASSERT_NE(testing::FindProgramWarning(per_min, "look like mm/s"), nullptr) << "F8 on weld moves: mm/s written as mm/min";
  GcodeReadOptions options;
  options.feed_unit = GcodeFeedUnit::kMmPerS;
  const ParsedProgram per_s = ReadGcode(mm_s, "bar.nc", options);
  EXPECT_EQ(testing::FindProgramWarning(per_s, "look like"), nullptr);
  ASSERT_EQ(per_s.motions.size(), 4u);
  EXPECT_NEAR(per_s.motions[1].speed_mm_s, 8.0, 1e-12);
  EXPECT_NEAR(per_s.motions[1].dwell_s, 1.5, 1e-12) << "G4 P1500: milliseconds";
  EXPECT_NEAR(per_s.motions[2].dwell_s, 12.0, 1e-12) << "G4 S12: seconds";
  EXPECT_NE(testing::FindProgramWarning(ReadGcode("G1 X1 F400\nM3\nG1 X2 F400\n", "a.nc", options), "look like mm/min"), nullptr);
}

}  // namespace
}  // namespace waam::planner
