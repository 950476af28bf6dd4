// Round trips of every program dialect: a planned path through the cell's motion, written, read back and turned
// into a plan again returns the same targets (positions within 1e-3 mm, orientations within 1e-3 deg, the same weld
// on/off, speeds within the dialect's resolution, the positioner angles) and the same path in the part frame.
#include <cmath>
#include <functional>
#include <regex>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/kinematics/cell_motion.h"
#include "planner/program/abb_rapid.h"
#include "planner/program/fanuc_ls.h"
#include "planner/program/gcode.h"
#include "planner/program/kuka_krl.h"
#include "planner/program/program_plan.h"
#include "planner/program/program_reader.h"
#include "planner/program/robot_program.h"
#include "planner/program/yaskawa_jbi.h"

namespace waam::planner {
namespace {

CellKinematics RoundTripCell(PositionerType type = PositionerType::kTiltRotate) {
  CellKinematics cell;
  cell.positioner.type = type;
  cell.arm = OpwArm::ArcMate100iC12();
  cell.X_FT.translation() = Eigen::Vector3d(400.0, 0.0, 0.0);
  cell.X_FT.linear() << 0, 0, 1, 0, -1, 0, 1, 0, 0;
  cell.X_WB.translation() = Eigen::Vector3d(1050.0, 0.0, 0.0);
  cell.X_WB.linear() = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  cell.positioner.p_BA = Eigen::Vector3d(0.0, 0.0, 500.0);
  cell.positioner.p_AC = Eigen::Vector3d(0.0, 0.0, 80.0);
  cell.positioner.X_CP.translation() = Eigen::Vector3d(0.0, 0.0, 20.0);
  return cell;
}

// Square passes: `layers` layers, each a travel to the corner and four welded sides (with 2 mm points on the first
// side), every layer grown along `build_dir` (tool direction = build direction).
Plan SquareLayers(int layers, const Eigen::Vector3d& build_dir) {
  Plan plan;
  plan.name = "round trip";
  const Eigen::Vector3d n = build_dir.normalized();
  for (int l = 0; l < layers; ++l) {
    LayerPath layer;
    layer.index = l;
    layer.build_dir_P = n;
    std::vector<Eigen::Vector2d> corners;
    for (int k = 0; k <= 10; ++k) corners.emplace_back(-20.0 + 4.0 * k, -20.0);
    corners.emplace_back(20.0, 20.0);
    corners.emplace_back(-20.0, 20.0);
    corners.emplace_back(-20.0, -20.0);
    for (std::size_t i = 0; i < corners.size(); ++i) {
      PathPoint p;
      p.p_P = Eigen::Vector3d(corners[i].x(), corners[i].y(), 0.0) + (1.5 * (l + 1)) * n;
      p.tool_dir_P = n;
      p.weld = i > 0;
      p.speed_mm_s = i > 0 ? 400.0 / 60.0 + 0.5 * l : 100.0;
      p.bead_width_mm = 6.0;
      p.bead_height_mm = 1.5;
      layer.points.push_back(p);
    }
    plan.layers.push_back(layer);
  }
  return plan;
}

struct Dialect {
  ProgramFormat format;
  std::function<std::string(const RobotProgram&, const CellKinematics&)> write;
  double weld_speed_tol_mm_s;    // the dialect's speed resolution
  double travel_speed_tol_mm_s;
  bool part_frame;               // positions compared in the part frame (G-code) rather than the user frame
};

// The station's pulses per degree the JBI round trip writes and reads with (a controller's parameters; any value
// above 500 keeps the whole-pulse rounding within 1e-3 deg).
constexpr std::array<double, 2> kStationPulsesPerDeg = {1365.3, 1137.8};

std::vector<Dialect> Dialects() {
  return {
      {ProgramFormat::kCsv, [](const RobotProgram& p, const CellKinematics&) { return ProgramToCsv(p); },
       0.05 / 60.0 + 1e-9, 0.05 / 60.0 + 1e-9, false},
      {ProgramFormat::kFanucLs,
       [](const RobotProgram& p, const CellKinematics&) { return ProgramToFanucLs(p, FanucLsOptions{}); },
       0.5 / 6.0 + 1e-9, 0.5 + 1e-9, false},
      {ProgramFormat::kAbbRapid,
       [](const RobotProgram& p, const CellKinematics& cell) {
         AbbRapidOptions options;
         options.X_RU = cell.X_WR.inverse() * ProgramUserFrame(cell);
         options.X_FT = cell.X_FT;
         return ProgramToAbbRapid(p, options);
       },
       5e-4 + 1e-9, 5e-4 + 1e-9, false},
      {ProgramFormat::kKukaKrl,
       [](const RobotProgram& p, const CellKinematics& cell) {
         KukaKrlOptions options;
         options.X_RU = cell.X_WR.inverse() * ProgramUserFrame(cell);
         const KukaKrlFiles files = ProgramToKukaKrl(p, options);
         return files.src + files.dat;
       },
       5e-4 + 1e-9, 5e-4 + 1e-9, false},
      {ProgramFormat::kYaskawaJbi,
       [](const RobotProgram& p, const CellKinematics& cell) {
         YaskawaJbiOptions options;
         options.X_RU = cell.X_WR.inverse() * ProgramUserFrame(cell);
         options.station_pulses_per_deg = kStationPulsesPerDeg;
         return ProgramToYaskawaJbi(p, options);
       },
       0.05 + 1e-9, 0.05 + 1e-9, false},
      {ProgramFormat::kGcode,
       [](const RobotProgram& p, const CellKinematics&) { return ProgramToGcode(p, GcodeOptions{}); },
       5e-4 / 60.0 + 1e-9, 5e-4 / 60.0 + 1e-9, true},
  };
}

double AngleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180.0 / kPi;
}

double DirAngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.normalized().cross(b.normalized()).norm(), a.normalized().dot(b.normalized())) * 180.0 / kPi;
}

// The program writes only the external axes the cell has.
void CheckExternalAxes(const std::string& text, ProgramFormat format, PositionerType type) {
  const bool tilt = type == PositionerType::kTiltRotate, none = type == PositionerType::kNone;
  switch (format) {
    case ProgramFormat::kCsv:
      EXPECT_EQ(text.find("tilt_deg") != std::string::npos, tilt);
      EXPECT_EQ(text.find("rotation_deg") != std::string::npos, !none);
      break;
    case ProgramFormat::kFanucLs:
      EXPECT_EQ(text.find("J2 =") != std::string::npos, tilt);
      EXPECT_EQ(text.find("GP2") != std::string::npos, !none);
      EXPECT_EQ(text.find("COORD") != std::string::npos, !none);
      break;
    case ProgramFormat::kAbbRapid:
      // eax_a and eax_b in use, eax_a alone, or neither (9E+09).
      EXPECT_EQ(text.find("],[9E+09,9E+09,9E+09") != std::string::npos, none);
      EXPECT_EQ(std::regex_search(text, std::regex(R"(\.[0-9]{3},9E\+09,9E\+09,9E\+09,9E\+09,9E\+09\]\])")), !tilt && !none);
      break;
    case ProgramFormat::kKukaKrl:
      // Unused axes 0.0 as KSS writes them.
      if (!tilt) {
        EXPECT_NE(text.find("E2 0.0000,"), std::string::npos);
      }
      if (none) {
        EXPECT_NE(text.find("E1 0.0000,"), std::string::npos);
      }
      break;
    case ProgramFormat::kGcode:
      // A and C words with a value (A3= C3= are the tool direction).
      EXPECT_EQ(std::regex_search(text, std::regex(R"( A-?[0-9]+\.[0-9])")), tilt);
      EXPECT_EQ(std::regex_search(text, std::regex(R"( C-?[0-9]+\.[0-9])")), !none);
      break;
    default:
      break;
  }
}

void CheckRoundTrip(const Plan& plan, const char* label, PositionerType type = PositionerType::kTiltRotate) {
  const CellKinematics cell = RoundTripCell(type);
  MotionOptions motion_options;
  motion_options.step_mm = 1e6;  // one sample per path point
  motion_options.rapid_speed_mm_s = 100.0;
  motion_options.rotation_rad = type == PositionerType::kTurntable ? 0.6 : 0.0;  // a turntable turned off its zero
  const std::vector<CellSample> motion = PlanCellMotion(cell, plan, motion_options, {});
  const RobotProgram program = BuildProgram(cell, motion, "rt");
  ASSERT_EQ(program.positioner, type);
  std::vector<PathPoint> planned;
  for (const LayerPath& layer : plan.layers) planned.insert(planned.end(), layer.points.begin(), layer.points.end());
  ASSERT_EQ(program.points.size(), planned.size());
  const Eigen::Isometry3d X_UW = ProgramUserFrame(cell).inverse();

  for (const Dialect& dialect : Dialects()) {
    SCOPED_TRACE(std::string(label) + " " + std::string(NameOf(dialect.format)));
    const std::string text = dialect.write(program, cell);
    CheckExternalAxes(text, dialect.format, type);
    JbiReadOptions jbi;
    jbi.station_pulses_per_deg = kStationPulsesPerDeg;
    const ParsedProgram parsed = ReadProgramText(text, "round_trip", dialect.format, GcodeReadOptions{}, jbi);
    EXPECT_TRUE(parsed.warnings.empty()) << parsed.warnings.front().what << " (line " << parsed.warnings.front().first_line
                                         << ")";
    ImportSettings settings;
    settings.rapid_speed_mm_s = 100.0;
    const std::vector<ResolvedTarget> targets = ResolveTargets(parsed, cell, settings);
    ASSERT_EQ(targets.size(), program.points.size()) << text.substr(0, 2000);
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const ProgramPoint& p = program.points[i];
      const ResolvedTarget& t = targets[i];
      EXPECT_NEAR(t.tilt_rad * 180.0 / kPi, p.tilt_deg, 1e-3) << "point " << i;
      EXPECT_NEAR(t.rotation_rad * 180.0 / kPi, p.rotation_deg, 1e-3) << "point " << i;
      EXPECT_EQ(t.weld, p.weld) << "point " << i;
      const double speed = t.speed_mm_s > 0.0 ? t.speed_mm_s : settings.rapid_speed_mm_s;
      EXPECT_NEAR(speed, p.speed_mm_s, p.weld ? dialect.weld_speed_tol_mm_s : dialect.travel_speed_tol_mm_s)
          << "point " << i;
      if (dialect.part_frame) {
        EXPECT_LT((t.p_P - p.p_P).norm(), 1e-3) << "point " << i;
        EXPECT_LT(DirAngleDeg(t.tool_dir_P, p.tool_dir_P), 1e-3) << "point " << i;
      } else {
        const Eigen::Isometry3d X_UT = X_UW * t.X_WT;
        EXPECT_LT((X_UT.translation() - p.tcp_mm).norm(), 1e-3) << "point " << i;
        const Eigen::Matrix3d R = (Eigen::AngleAxisd(p.a_deg * kPi / 180.0, Eigen::Vector3d::UnitZ()) *
                                   Eigen::AngleAxisd(p.b_deg * kPi / 180.0, Eigen::Vector3d::UnitY()) *
                                   Eigen::AngleAxisd(p.c_deg * kPi / 180.0, Eigen::Vector3d::UnitX()))
                                      .toRotationMatrix();
        EXPECT_LT(AngleDeg(X_UT.linear(), R), 1e-3) << "point " << i;
      }
    }
    // The plan again: the same points in the part frame (to the resolution the program's angles allow), the same
    // welds, the same layers.
    const ImportedPlan imported = ProgramToPlan(parsed, cell, settings);
    ASSERT_EQ(imported.points, planned.size());
    // The cell motion of the imported plan follows the program's positioner angles rather than solving its own.
    const std::vector<CellSample> again = PlanCellMotion(cell, imported.plan, motion_options, {});
    ASSERT_EQ(again.size(), program.points.size());
    for (std::size_t i = 0; i < again.size(); ++i) {
      EXPECT_NEAR(again[i].q[6] * kDeg, program.points[i].tilt_deg, 1e-3) << "point " << i;
      EXPECT_NEAR(again[i].q[7] * kDeg, program.points[i].rotation_deg, 1e-3) << "point " << i;
    }
    EXPECT_EQ(imported.plan.layers.size(), plan.layers.size());
    std::size_t k = 0;
    for (const LayerPath& layer : imported.plan.layers) {
      for (const PathPoint& q : layer.points) {
        const PathPoint& p = planned[k++];
        EXPECT_LT((q.p_P - p.p_P).norm(), 0.02) << "point " << k - 1;
        EXPECT_LT(DirAngleDeg(q.tool_dir_P, p.tool_dir_P), 2e-3) << "point " << k - 1;
        EXPECT_EQ(q.weld, p.weld) << "point " << k - 1;
      }
    }
  }
}

TEST(ProgramRoundTripTest, PlanarLayersComeBackFromEveryDialect) {
  CheckRoundTrip(SquareLayers(3, Eigen::Vector3d::UnitZ()), "planar");
}

TEST(ProgramRoundTripTest, TiltedBuildDirectionComesBackFromEveryDialect) {
  // The positioner tilts the part by about 27 deg and turns it: both group-2 axes and the torch orientation move.
  CheckRoundTrip(SquareLayers(3, Eigen::Vector3d(0.3, 0.5, 1.0)), "multi-axis");
}

TEST(ProgramRoundTripTest, TurntableProgramsComeBackFromEveryDialect) {
  // One external axis: the table's rotation (E1, eax_a, GP2 J1, C), turned 0.6 rad; the tilt is nowhere.
  CheckRoundTrip(SquareLayers(3, Eigen::Vector3d::UnitZ()), "turntable planar", PositionerType::kTurntable);
  // Layers the turntable cannot turn up: the torch follows the tool direction, tilted, and comes back so.
  CheckRoundTrip(SquareLayers(3, Eigen::Vector3d(0.3, 0.5, 1.0)), "turntable tilted", PositionerType::kTurntable);
}

TEST(ProgramRoundTripTest, NoPositionerProgramsComeBackFromEveryDialect) {
  CheckRoundTrip(SquareLayers(3, Eigen::Vector3d(0.3, 0.5, 1.0)), "none", PositionerType::kNone);
}

TEST(ProgramRoundTripTest, AxisTheCellLacksIsNotedAndHeldAtZero) {
  // A two-axis program (tilt 20 deg) read on a turntable cell: the numbered axes go to the table in order (E1 = the
  // rotation), the second is one the cell lacks: noted, held at 0.
  const CellKinematics cell = RoundTripCell(PositionerType::kTurntable);
  ParsedProgram program;
  program.format = ProgramFormat::kKukaKrl;
  ProgramMotion m;
  m.has_pose = true;
  m.X_UT.translation() = Eigen::Vector3d(1000.0, 0.0, 0.0);
  m.has_positioner = true;
  m.positioner_numbered = true;
  m.tilt_rad = 0.35;
  m.rotation_rad = 0.5;
  m.line = 7;
  program.motions = {m, m};
  const std::vector<ResolvedTarget> targets = ResolveTargets(program, cell, ImportSettings{});
  EXPECT_EQ(targets[0].rotation_rad, 0.35);
  EXPECT_EQ(targets[0].tilt_rad, 0.0);
  EXPECT_TRUE(targets[0].missing_axis);
  const ImportedPlan imported = ProgramToPlan(program, cell, ImportSettings{});
  ASSERT_FALSE(imported.warnings.empty());
  EXPECT_THAT(imported.warnings.back().what, ::testing::HasSubstr("cell.positioner.type turntable"));
  EXPECT_EQ(imported.warnings.back().first_line, 7);
}

TEST(ProgramRoundTripTest, GivenPositionerAnglesDriveTheCellMotionInsteadOfSolvedOnes) {
  // Vertical layers: the solver keeps the tilt at 0. The second layer's points carry a program's own angles.
  Plan plan = SquareLayers(2, Eigen::Vector3d::UnitZ());
  for (PathPoint& p : plan.layers[1].points) p.positioner_rad = Eigen::Vector2d(0.3, -0.8);
  MotionOptions options;
  options.step_mm = 1e6;  // one sample per path point
  options.rapid_speed_mm_s = 100.0;
  const std::vector<CellSample> motion = PlanCellMotion(RoundTripCell(), plan, options, {});
  const std::size_t first = plan.layers[0].points.size();
  ASSERT_EQ(motion.size(), first + plan.layers[1].points.size());
  for (std::size_t i = 0; i < motion.size(); ++i) {
    EXPECT_NEAR(motion[i].q[6], i < first ? 0.0 : 0.3, 1e-12) << "sample " << i;
    if (i >= first) {
      EXPECT_NEAR(motion[i].q[7], -0.8, 1e-12) << "sample " << i;
    }
  }
  // Halfway along a move the angles are halfway between the previous point's and the given ones.
  options.step_mm = 1.0;
  const std::vector<CellSample> fine = PlanCellMotion(RoundTripCell(), plan, options, {});
  std::size_t entry = 0;
  while (fine[entry].point < static_cast<int>(first)) ++entry;  // the samples of the move into layer 2
  std::size_t last = entry;
  while (fine[last + 1].point == static_cast<int>(first)) ++last;
  ASSERT_GT(last, entry);
  const double tilt_before = fine[entry - 1].q[6];
  for (std::size_t i = entry; i <= last; ++i) {
    const double f = static_cast<double>(i - entry + 1) / static_cast<double>(last - entry + 1);
    EXPECT_NEAR(fine[i].q[6], tilt_before + f * (0.3 - tilt_before), 1e-12) << "sample " << i;
  }
}

}  // namespace
}  // namespace waam::planner
