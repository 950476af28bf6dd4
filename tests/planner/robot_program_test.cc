// Tests of the program writers: Euler angles rebuild the rotation, the CSV and LS texts hold every point.
#include "planner/program/robot_program.h"

#include <random>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "planner/program/fanuc_ls.h"

namespace waam::planner {
namespace {
using ::testing::HasSubstr;

TEST(RobotProgramTest, EulerAnglesRebuildTheRotation) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Matrix3d R = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    const Eigen::Vector3d abc = EulerZyx(R);
    // eq. 5.5: R = Rz(A) Ry(B) Rx(C).
    const Eigen::Matrix3d back = (Eigen::AngleAxisd(abc[0], Eigen::Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(abc[1], Eigen::Vector3d::UnitY()) *
                                  Eigen::AngleAxisd(abc[2], Eigen::Vector3d::UnitX()))
                                     .toRotationMatrix();
    EXPECT_LT((back - R).norm(), 1e-9) << "rotation " << i;
  }
}

RobotProgram TwoPassProgram() {
  RobotProgram program;
  program.name = "TEST";
  for (int i = 0; i < 6; ++i) {
    ProgramPoint p;
    p.point = i;
    p.tcp_mm = Eigen::Vector3d(900.0 + i, 10.0 * i, -150.0);
    p.speed_mm_s = i % 3 == 0 ? 100.0 : 6.667;
    p.weld = i % 3 != 0;  // travel to 0, weld 1-2, travel to 3, weld 4-5
    p.q << 0.0, 0.1, 0.2, 0.0, -1.5, 0.0;
    p.tilt_deg = 10.0;
    p.rotation_deg = -30.0;
    program.points.push_back(p);
  }
  return program;
}

TEST(RobotProgramTest, CsvHasAHeaderAndOneRowPerPoint) {
  const std::string csv = ProgramToCsv(TwoPassProgram());
  std::istringstream in(csv);
  std::string line;
  int rows = 0;
  std::getline(in, line);
  EXPECT_THAT(line, HasSubstr("x_mm,y_mm,z_mm,a_deg,b_deg,c_deg,tilt_deg,rotation_deg"));
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 6);
  EXPECT_THAT(csv, HasSubstr("905.000,50.000,-150.000"));
}

TEST(RobotProgramTest, FanucLsHasArcStartsEndsAndTheSecondGroup) {
  const std::string ls = ProgramToFanucLs(TwoPassProgram(), FanucLsOptions{});
  EXPECT_THAT(ls, HasSubstr("/PROG  TEST"));
  EXPECT_THAT(ls, HasSubstr("DEFAULT_GROUP\t= 1,1,*,*,*;"));
  std::size_t starts = 0, ends = 0;
  for (std::size_t at = ls.find("Arc Start[1]"); at != std::string::npos; at = ls.find("Arc Start[1]", at + 1)) ++starts;
  for (std::size_t at = ls.find("Arc End[1]"); at != std::string::npos; at = ls.find("Arc End[1]", at + 1)) ++ends;
  EXPECT_EQ(starts, 2u) << "one arc start per pass";
  EXPECT_EQ(ends, 2u) << "one arc end per pass";
  EXPECT_THAT(ls, HasSubstr("L P[2] 40cm/min CNT100 COORD")) << "6.667 mm/s = 40 cm/min";
  EXPECT_THAT(ls, HasSubstr("L P[4] 100mm/sec FINE")) << "travel moves";
  EXPECT_THAT(ls, HasSubstr("CONFIG : 'N U T, 0, 0, 0'"));
  EXPECT_THAT(ls, HasSubstr("GP2:"));
  EXPECT_THAT(ls, HasSubstr("J1 =     10.000 deg,\tJ2 =    -30.000 deg"));
  EXPECT_THAT(ls, HasSubstr("P[6]{"));
  EXPECT_THAT(ls, HasSubstr("/END"));
}

}  // namespace
}  // namespace waam::planner
