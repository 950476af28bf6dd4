// The ABB RAPID and Yaskawa INFORM readers on their controllers' grammar: procedures and their calls, multi-line
// aggregates, the tools and work objects or user frames a program uses, computed targets, speeds, arc and waits.
#include <cmath>
#include <functional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/program/program_reader.h"
#include "tests/planner/program_files.h"

namespace waam::planner {
namespace {
using ::testing::HasSubstr;

std::string ErrorOf(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// A bar of two layers on a plate, as a RobotWare Arc program lays it out: the layer a procedure main calls twice.
const char* const kRapidBar = R"(%%%
  VERSION:1
  LANGUAGE:ENGLISH
%%%
MODULE BAR(SYSMODULE)
  ! tool and work object of the cell
  PERS tooldata tTorch:=[TRUE,[[10,0,350],[0.965926,0,0.258819,0]],[3,[0,0,100],[1,0,0,0],0,0,0]];
  TASK PERS wobjdata wPlate:=[FALSE,TRUE,"",[[800,-100,300],[0.707107,0,0,0.707107]],
                              [[0,0,0],[1,0,0,0]]];
  CONST speeddata vBead:=[8,500,5000,1000];
  PERS welddata wd1:=[6,0,[5,0,24,120,0,0,0,0,0],[0,0,0,0,0,0,0,0,0]];
  CONST num nDwell:=30;
  CONST num nLift:=20;
  CONST robtarget pA:=[[0,0,2],[0,1,0,0],[0,0,0,0],
                       [9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
  CONST robtarget pB:=[[100,0,2],[0,1,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];

  PROC main()
    VelSet 50, 400;
    MoveJ Offs(pA,0,0,nLift),v1000,z10,tTorch\WObj:=wPlate;
    Layer;
    WaitTime nDwell;
    IF nDwell > 0 THEN
      Set doWeldOn;
      MoveL Offs(pA,0,0,1.8),vBead,fine,tTorch\WObj:=wPlate;
      Reset doWeldOn;
    ENDIF
    MoveL RelTool(pA,0,0,-10\Rz:=90),v100\V:=50,fine,tTorch\WObj:=wPlate;
  ENDPROC

  PROC Layer()
    ArcLStart pA,v100,seam1,wd1,fine,tTorch\WObj:=wPlate;
    ArcLEnd pB,v100,seam1,wd1,fine,tTorch\WObj:=wPlate;
  ENDPROC
ENDMODULE
)";

TEST(RapidGrammarTest, MainRunsItsProceduresWithTheModulesToolWorkObjectAndData) {
  const ParsedProgram p = ReadAbbRapid(kRapidBar, "bar.mod");
  EXPECT_EQ(p.name, "BAR");
  ASSERT_EQ(p.motions.size(), 5u);
  Eigen::Isometry3d X_RU = Eigen::Isometry3d::Identity();
  X_RU.translation() = Eigen::Vector3d(800, -100, 300);
  X_RU.linear() = Eigen::AngleAxisd(kPi / 2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  // Offs(pA, 0, 0, nLift): 20 mm up in the work object; VelSet 50 % of v1000 = 500, capped at 400 mm/s.
  EXPECT_LT((p.motions[0].X_UT.translation() - X_RU * Eigen::Vector3d(0, 0, 22)).norm(), 1e-9);
  EXPECT_EQ(p.motions[0].frame, TargetFrame::kRobot);
  EXPECT_NEAR(p.motions[0].speed_mm_s, 400.0, 1e-12);
  // Layer: ArcLStart moves (arc off) at v100 under VelSet (50 mm/s), ArcLEnd welds at wd1's weld_speed, 6 mm/s.
  EXPECT_FALSE(p.motions[1].weld);
  EXPECT_NEAR(p.motions[1].speed_mm_s, 50.0, 1e-12);
  EXPECT_TRUE(p.motions[2].weld);
  EXPECT_NEAR(p.motions[2].speed_mm_s, 3.0, 1e-12) << "weld_speed 6 mm/s at VelSet's 50 %";
  EXPECT_LT((p.motions[2].X_UT.translation() - X_RU * Eigen::Vector3d(100, 0, 2)).norm(), 1e-9);
  EXPECT_NEAR(p.motions[2].dwell_s, 30.0, 1e-12) << "WaitTime nDwell after Layer";
  // Set doWeldOn / Reset: the arc on for the MoveL at vBead (8 mm/s, VelSet 4 mm/s); IF's statements run, warned.
  EXPECT_TRUE(p.motions[3].weld);
  EXPECT_NEAR(p.motions[3].speed_mm_s, 4.0, 1e-12);
  EXPECT_NE(testing::FindProgramWarning(p, "RAPID IF not followed"), nullptr);
  // RelTool(pA, 0, 0, -10 \Rz:=90): 10 mm back along the tool's z (pA's z points down: 10 mm up), turned about z;
  // \V:=50 in place of v100's speed, VelSet applied.
  const Eigen::Isometry3d& X = p.motions[4].X_UT;
  EXPECT_LT((X.translation() - X_RU * Eigen::Vector3d(0, 0, 12)).norm(), 1e-9);
  const Eigen::Matrix3d R_pA = Eigen::Quaterniond(0, 1, 0, 0).toRotationMatrix();
  const Eigen::Matrix3d R = X_RU.linear() * R_pA * Eigen::AngleAxisd(kPi / 2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_LT((X.linear() - R).norm(), 1e-9);
  EXPECT_NEAR(p.motions[4].speed_mm_s, 25.0, 1e-12);
  // The tool: tTorch, its tframe in the flange frame.
  for (const ProgramMotion& m : p.motions) {
    ASSERT_TRUE(m.has_tool);
    EXPECT_EQ(m.tool_name, "tTorch");
    // tframe (10, 0, 350) in ABB's flange frame (z along the flange normal) is (350, 0, -10) in the twin's (x along it).
    EXPECT_LT((m.X_FT.translation() - Eigen::Vector3d(350, 0, -10)).norm(), 1e-9);
  }
}

TEST(RapidGrammarTest, WhatTheControllerRefusesIsRefusedOnOneLine) {
  auto read = [](const std::string& text) { return ErrorOf([&] { (void)ReadAbbRapid(text, "bad.mod"); }); };
  const std::string bar = kRapidBar;
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string s = bar;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  EXPECT_THAT(read(replace("[[10,0,350],[0.965926,0,0.258819,0]]", "[[10,0,350]]")),
              HasSubstr("bad.mod:7: tooldata must be [robhold,[[x,y,z],[q1..q4]],[mass,[cog],[aom],ix,iy,iz]]"));
  EXPECT_THAT(read(replace("ArcLEnd pB,v100,seam1,wd1,fine,tTorch", "ArcLEnd pC,v100,seam1,wd1,fine,tTorch")),
              HasSubstr("bad.mod:33: pC is used but not declared as a ROBTARGET"));
  EXPECT_THAT(read(replace("ArcLEnd pB,v100,seam1,wd1,fine,tTorch", "ArcLEnd pB,v100,fine,tTorch")),
              HasSubstr("bad.mod:33: ARCLEND needs 6 arguments, got 4"));
  EXPECT_THAT(read(replace("  PROC Layer()", "  PROC Layer()\n    Layer;")),
              HasSubstr("procedure calls nested deeper than 16 (LAYER calls itself?)"));
  EXPECT_THAT(read(replace("MoveJ Offs(pA,0,0,nLift)", "MoveJ Offs(pA,0,0,nLift")), HasSubstr("bad.mod:20: OFFS( without its ')'"));
}

// A bar in user frame 3 with tool 2, as a Yaskawa controller saves it: arc start and crater times, a dwell, a circle.
const char* const kJbiBar = R"(/JOB
//NAME BAR
//POS
///NPOS 5,0,0,0,0,0
///USER 3
///TOOL 2
///POSTYPE USER
///RECTAN
///RCONF 0,0,0,0,0,0,0,0
C00000=0.000,0.000,20.000,180.0000,0.0000,0.0000
C00001=0.000,0.000,2.000,180.0000,0.0000,0.0000
C00002=100.000,0.000,2.000,180.0000,0.0000,0.0000
C00003=110.000,10.000,2.000,180.0000,0.0000,0.0000
C00004=100.000,20.000,2.000,180.0000,0.0000,0.0000
//INST
///DATE 2025/06/02 10:00
///ATTR SC,RW
///GROUP1 RB1
NOP
'bar, one layer
MOVJ C00000 VJ=25.00
MOVL C00001 V=50.0 PL=0
ARCON AC=180 AV=19.5 T=0.50
MOVL C00002 V=8.0 PL=0
MOVC C00002 V=8.0
MOVC C00003 V=8.0
MOVC C00004 V=8.0 UNTIL IN#(3)=ON
ARCOF AEF#(1) T=1.00
TIMER T=60.00
MOVL C00000 V=I000
END
)";

ProgramFrames BarFrames() {
  ProgramFrames frames;
  frames.uframe[3] = {500.0, 100.0, 0.0, 0.0, 0.0, 90.0};   // x y z rx ry rz: turned 90 deg about z
  frames.utool[2] = std::array<double, 6>{0.0, 0.0, 380.0, 0.0, 0.0, 0.0};
  return frames;
}

TEST(InformGrammarTest, UserFramesToolsArcTimesAndCircles) {
  const ParsedProgram p = ReadYaskawaJbi(kJbiBar, "bar.JBI", {}, BarFrames());
  EXPECT_EQ(p.name, "BAR");
  ASSERT_EQ(p.motions.size(), 5u);
  Eigen::Isometry3d X_RU = Eigen::Isometry3d::Identity();
  X_RU.translation() = Eigen::Vector3d(500, 100, 0);
  X_RU.linear() = Eigen::AngleAxisd(kPi / 2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_EQ(p.motions[0].frame, TargetFrame::kRobot);
  EXPECT_LT((p.motions[0].X_UT.translation() - X_RU * Eigen::Vector3d(0, 0, 20)).norm(), 1e-9);
  EXPECT_EQ(p.motions[0].kind, MotionKind::kJoint);
  EXPECT_TRUE(p.motions[0].has_tool);
  EXPECT_EQ(p.motions[0].tool_name, "TOOL 2");
  EXPECT_NEAR(p.motions[0].X_FT.translation().z(), 380.0, 1e-12);
  // ARCON T=0.50 waits at C00001 (arc on), the weld at V=8.0, the circle from where the robot stands (C00002).
  EXPECT_NEAR(p.motions[1].dwell_s, 0.5, 1e-12);
  EXPECT_TRUE(p.motions[2].weld);
  EXPECT_NEAR(p.motions[2].speed_mm_s, 8.0, 1e-12);
  EXPECT_EQ(p.motions[3].kind, MotionKind::kCircular);
  EXPECT_LT((p.motions[3].via - X_RU * Eigen::Vector3d(110, 10, 2)).norm(), 1e-9);
  EXPECT_TRUE(p.motions[3].weld);
  // ARCOF T=1.00 (crater) and TIMER T=60.00 at the circle's end.
  EXPECT_NEAR(p.motions[3].dwell_s, 61.0, 1e-12);
  EXPECT_FALSE(p.motions[4].weld);
  EXPECT_LE(p.motions[4].speed_mm_s, 0.0) << "V=I000: a variable, the scenario's speed";
  EXPECT_NE(testing::FindProgramWarning(p, "V=I000"), nullptr);
  EXPECT_NE(testing::FindProgramWarning(p, "UNTIL"), nullptr);
}

TEST(InformGrammarTest, WhatTheControllerRefusesIsRefusedOnOneLine) {
  auto read = [](const std::string& text, const ProgramFrames& frames) {
    return ErrorOf([&] { (void)ReadYaskawaJbi(text, "bad.JBI", {}, frames); });
  };
  const std::string bar = kJbiBar;
  EXPECT_THAT(read(bar, {}), HasSubstr("bad.JBI:21: a position taught in user frame 3, which the job does not define: "
                                       "give program.frames.uframe.3"));
  ProgramFrames no_tool = BarFrames();
  no_tool.utool.erase(2);
  no_tool.utool[1] = std::nullopt;
  EXPECT_THAT(read(bar, no_tool), HasSubstr("bad.JBI:21: a position taught with tool 2, which the job does not define"));
  std::string local = bar;
  local.replace(local.find("MOVL C00000 V=I000"), 18, "MOVL LP000 V=10.0");
  EXPECT_THAT(read(local, BarFrames()), HasSubstr("bad.JBI:30: MOVL to a local position variable LP000"));
  std::string timer = bar;
  timer.replace(timer.find("TIMER T=60.00"), 13, "TIMER");
  EXPECT_THAT(read(timer, BarFrames()), HasSubstr("bad.JBI:29: TIMER without its T="));
}

}  // namespace
}  // namespace waam::planner
