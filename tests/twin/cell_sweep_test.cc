// Tests of the continuous cell check: a thin plate the torch sweeps through between two samples (a positioner turn
// over a 1 mm move) is found with its time by the continuous mode and missed by the discrete one; the certified
// clearance is a lower bound of the distances along the joint-space lines and close to their minimum.
#include "twin/cell/cell_sweep.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/cell_files.h"
#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/kinematics/positioner.h"
#include "planner/scenario/scenario_document.h"
#include "tests/twin/test_plans.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/cell_section.h"

namespace waam::twin {
namespace {
using analysis::LoadCell;
namespace fs = std::filesystem;

twin::CellSettings OkSettings() {
  const fs::path file = fs::path(WAAM_SOURCE_DIR) / "scenarios" / "cell" / "cell_ok.yaml";
  YamlMap top(LoadYamlFile(file.string()), "", file.string());  // the document as analysis::LoadScenarioTop reads it
  twin::CellSettings settings = ParseCellSection(top);
  settings.part_collision = false;           // the cell bodies only
  settings.resolve = CellResolve::kFixed;    // the motion as planned
  return settings;
}

planner::PathPoint Point(double x, double y, double rotation_rad, bool weld) {
  planner::PathPoint p;
  p.p_P = Eigen::Vector3d(x, y, 1.5);
  p.bead_width_mm = 6.0;
  p.bead_height_mm = 1.5;
  p.speed_mm_s = 5.0;
  p.weld = weld;
  p.positioner_rad = Eigen::Vector2d(0.0, rotation_rad);
  return p;
}

// A program's pass near the plate's edge, then a 1 mm arc-off move over which its own positioner angles turn the
// table by 70 deg, then a second pass: the torch swings about 120 mm through the cell between two samples.
planner::Plan SwingPlan() {
  planner::Plan plan;
  planner::LayerPath layer;
  layer.points = {Point(100.0, -10.0, 0.0, false), Point(100.0, 10.0, 0.0, true), Point(100.0, 11.0, 1.22, false),
                  Point(100.0, 30.0, 1.22, true)};
  plan.layers.push_back(layer);
  return plan;
}

// The built-in cell (placed as cell_ok places it) with a 1 mm thin plate, 80 x 80 mm, fixed in the world with its
// centre at p_W (mm) and its normal along n_W.
CellModel CellWithPlate(const Eigen::Vector3d& p_W, const Eigen::Vector3d& n_W) {
  std::ifstream in(analysis::BuiltinCellPath());
  std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Eigen::Vector3d p = p_W / 1000.0;
  const std::string oriented = "<geom name=\"planted_plate\" type=\"box\" size=\"0.04 0.04 0.0005\" pos=\"" +
                               std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) +
                               "\" zaxis=\"" + std::to_string(n_W.x()) + " " + std::to_string(n_W.y()) + " " +
                               std::to_string(n_W.z()) + "\"/>";
  const std::string anchor = "<worldbody>";
  xml.insert(xml.find(anchor) + anchor.size(), "\n    " + oriented);
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  X_WB.translate(Eigen::Vector3d(1050.0, 0.0, 0.0));
  X_WB.rotate(Eigen::AngleAxisd(kPi / 2.0, Eigen::Vector3d::UnitZ()));
  const CellModel::RobotInfo info{.name = "FANUC ARC Mate 100iC/12", .source = "builtin"};
  return CellModel::FromXml(MjcfSource{.xml = xml, .file = analysis::BuiltinCellPath(), .assets = {}, .builtin = false},
                            info, Eigen::Isometry3d::Identity(), X_WB);
}

int Collisions(const CheckReport& r, bool* between, double* t_s) {
  int n = 0;
  for (const CheckViolation& v : r.violations) {
    if (v.kind != ViolationKind::kCollision) continue;
    ++n;
    *between = *between || v.between_samples;
    if (v.t_s >= 0.0) *t_s = v.t_s;
  }
  return n;
}

TEST(CellSweepTest, ThinPlateBetweenTwoSamplesIsFoundOnlyByTheContinuousCheck) {
  twin::CellSettings settings = OkSettings();
  const planner::Plan plan = SwingPlan();
  const CheckReport plain = CheckPlan(LoadCell(settings), plan, settings, 100.0, nullptr);
  // The swing: the largest TCP move between two samples.
  std::size_t k = 1;
  double largest = 0.0;
  for (std::size_t i = 1; i < plain.motion.size(); ++i) {
    const double move = (plain.motion[i].X_WT.translation() - plain.motion[i - 1].X_WT.translation()).norm();
    if (move > largest) {
      largest = move;
      k = i;
    }
  }
  ASSERT_GT(largest, 60.0) << "the positioner turn must swing the torch far between two samples";
  const Eigen::Vector3d a = plain.motion[k - 1].X_WT.translation(), b = plain.motion[k].X_WT.translation();
  const Eigen::Vector3d up = -plain.motion[k].X_WT.linear().col(2);
  // The plate across the swing's chord, 100 mm up the torch from the TCP: both samples lie 60 mm or more from it.
  const CellModel cell = CellWithPlate(0.5 * (a + b) + 100.0 * up, (b - a).normalized());

  settings.check_mode = CheckMode::kDiscrete;
  const CheckReport discrete = CheckPlan(cell, plan, settings, 100.0, nullptr);
  settings.check_mode = CheckMode::kContinuous;
  const CheckReport continuous = CheckPlan(cell, plan, settings, 100.0, nullptr);

  bool between = false;
  double t_s = -1.0;
  EXPECT_EQ(Collisions(discrete, &between, &t_s), 0) << "the discrete check steps over the plate (the known miss)";
  EXPECT_EQ(discrete.mode, CheckMode::kDiscrete);
  EXPECT_GE(Collisions(continuous, &between, &t_s), 1) << "the continuous check must find the plate";
  EXPECT_EQ(continuous.mode, CheckMode::kContinuous);
  EXPECT_TRUE(between) << "the contact lies strictly between two samples";
  EXPECT_GT(t_s, plain.motion[k - 1].t_s) << "first contact after the sample before the swing";
  EXPECT_LT(t_s, plain.motion[k].t_s) << "first contact before the sample after it";
  EXPECT_NEAR(continuous.first_contact_s, t_s, 1e-12);
  EXPECT_LT(continuous.certified_clearance_mm, 0.0) << "a penetrating contact: minus its depth";
  // Without the plate the continuous check passes and certifies a clearance.
  const CheckReport clear = CheckPlan(LoadCell(settings), plan, settings, 100.0, nullptr);
  EXPECT_TRUE(clear.ok);
  EXPECT_GT(clear.certified_clearance_mm, 0.0);
}

TEST(CellSweepTest, CertifiedClearanceBoundsTheDistancesAlongTheLines) {
  const twin::CellSettings settings = OkSettings();
  const CellModel cell = LoadCell(settings);
  const CellCollisionGeometry geometry = cell.CollisionGeometry();
  ASSERT_TRUE(geometry.unsupported.empty()) << geometry.unsupported;
  const CheckReport r = CheckPlan(cell, SwingPlan(), settings, 100.0, nullptr);
  const SweepResult sweep = SweepMotion(cell, geometry, r.motion, SweepOptions{});
  ASSERT_TRUE(sweep.contacts.empty());
  // Every pair at 8 points along every joint-space line, by GJK.
  CellState state(cell);
  std::vector<Eigen::Isometry3d> X;
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < r.motion.size(); ++i) {
    for (int k = 0; k < 8; ++k) {
      const double f = k / 8.0;
      state.SetJoints(r.motion[i - 1].q + f * (r.motion[i].q - r.motion[i - 1].q));
      state.ShapePoses(geometry, &X);
      for (const std::array<int, 2>& p : geometry.pairs) {
        const ConvexDistance d = ShapeDistance(geometry.shapes[p[0]], X[p[0]], geometry.shapes[p[1]], X[p[1]], 0.01);
        smallest = std::min(smallest, d.upper_mm);
      }
    }
  }
  EXPECT_LE(sweep.certified_clearance_mm, smallest) << "certified: no distance along the motion is smaller";
  EXPECT_GE(sweep.certified_clearance_mm, smallest - std::max(0.1, 0.05 * smallest) - 0.01)
      << "and within the resolution of the smallest";
  EXPECT_LT(sweep.distance_queries, geometry.pairs.size() * r.motion.size())
      << "advancement skips most of the queries a check of every pair at every sample makes";
}

int PartCollisions(const CheckReport& r, bool* between, double* t_s) {
  int n = 0;
  for (const CheckViolation& v : r.violations) {
    if (v.kind != ViolationKind::kCollision || v.body1 != "part") continue;
    ++n;
    *between = *between || v.between_samples;
    *t_s = v.t_s;
  }
  return n;
}

std::size_t LargestMove(const std::vector<planner::CellSample>& motion) {
  std::size_t k = 1;
  double largest = 0.0;
  for (std::size_t i = 1; i < motion.size(); ++i) {
    const double move = (motion[i].X_WT.translation() - motion[i - 1].X_WT.translation()).norm();
    if (move > largest) {
      largest = move;
      k = i;
    }
  }
  return k;
}

// The torch against the part built so far: while the table turns 70 deg under a 1 mm move, the nozzle leaves the
// move's line by tens of mm in the part frame. A wall laid first where it passes halfway is clipped between two
// samples, with the nozzle clear of the metal at every sample.
TEST(CellSweepTest, WallTheSwingClipsBetweenTwoSamplesIsFoundOnlyByTheContinuousCheck) {
  twin::CellSettings settings = OkSettings();
  settings.part_collision = true;
  settings.check_mode = CheckMode::kContinuous;
  const CellModel cell = LoadCell(settings);
  const CellCollisionGeometry geometry = cell.CollisionGeometry();
  const CheckReport plain = CheckPlan(cell, SwingPlan(), settings, 100.0, nullptr);
  ASSERT_TRUE(plain.ok);
  const std::size_t k = LargestMove(plain.motion);
  const planner::Joints8 q_mid = 0.5 * (plain.motion[k - 1].q + plain.motion[k].q);
  std::vector<Eigen::Isometry3d> X_WL;
  LinkPosesAt(geometry, q_mid, &X_WL);
  const planner::CellKinematics kin = PartKinematics(cell, settings);
  const Eigen::Vector3d mid_P = ((kin.X_WB * planner::PartPose(kin.positioner, q_mid[6], q_mid[7])).inverse() *
                                 X_WL[geometry.nozzle_link] * geometry.X_LN).translation();
  // The samples' nozzle stands on x = 100 mm; the wall below along y at the nozzle's x halfway: at the samples more
  // than its half width (3 mm) and the nozzle's radius (11 mm) away.
  ASSERT_GT(std::abs(mid_P.x() - 100.0), 18.0) << "halfway the nozzle is far from the move's line in the part frame";

  // The wall: one 20 mm pass whose top is 30 mm up (the map's metal stands below each bead's top), then a travel up
  // and over to the swing.
  const auto at = [](double x, double y, double z, bool weld) {
    planner::PathPoint p = Point(x, y, 0.0, weld);
    p.p_P.z() = z;
    return p;
  };
  planner::Plan plan;
  planner::LayerPath wall;
  wall.points = {at(mid_P.x(), mid_P.y() - 10.0, 30.0, false), at(mid_P.x(), mid_P.y() + 10.0, 30.0, true),
                 at(mid_P.x(), mid_P.y() + 10.0, 80.0, false), at(100.0, -10.0, 80.0, false)};
  plan.layers = {wall, SwingPlan().layers[0]};

  const CheckReport continuous = CheckPlan(cell, plan, settings, 100.0, nullptr);
  settings.check_mode = CheckMode::kDiscrete;
  const CheckReport discrete = CheckPlan(cell, plan, settings, 100.0, nullptr);
  const std::size_t swing = LargestMove(continuous.motion);
  bool between = false;
  double t_s = -1.0;
  EXPECT_EQ(PartCollisions(discrete, &between, &t_s), 0) << "the discrete check steps over the wall (the known miss)";
  ASSERT_EQ(PartCollisions(continuous, &between, &t_s), 1) << "the continuous check must find the wall";
  EXPECT_TRUE(between) << "the contact lies strictly between two samples";
  EXPECT_GT(t_s, continuous.motion[swing - 1].t_s) << "first contact after the sample before the swing";
  EXPECT_LT(t_s, continuous.motion[swing].t_s) << "and before the sample after it";
  EXPECT_LT(continuous.part_clearance_mm, 0.0) << "a penetrating contact: minus its depth";
  // Without the wall the swing passes and the nozzle's clearance from its own beads is certified.
  EXPECT_GT(plain.part_clearance_mm, 0.0);
  EXPECT_TRUE(std::isfinite(plain.part_clearance_mm));
}

// The pairs the distance queries take are MuJoCo's: none of the built-in cell's <exclude> body pairs (the pedestal
// and the tilt housing it would reach from 45 deg of tilt), and the pairs no rule excludes (the arm's base against the
// tilt housing).
// A geom the continuous check cannot bound (a height field: no convex shape for the distance queries) sends the
// check back to the discrete mode, with the geom and the reason in the report, never silently.
TEST(CellSweepTest, AnUnboundedGeomFallsBackToDiscreteWithTheReason) {
  std::ifstream in(analysis::BuiltinCellPath());
  std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string anchor = "<worldbody>";
  ASSERT_NE(xml.find(anchor), std::string::npos);
  xml.insert(xml.find(anchor),
             "<asset><hfield name=\"bumps\" nrow=\"2\" ncol=\"2\" size=\"0.2 0.2 0.01 0.01\"/></asset>\n");
  xml.insert(xml.find(anchor) + anchor.size(),
             "\n<geom name=\"floor_bumps\" type=\"hfield\" hfield=\"bumps\" pos=\"3 3 0\"/>");
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  X_WB.translate(Eigen::Vector3d(1050.0, 0.0, 0.0));
  X_WB.rotate(Eigen::AngleAxisd(kPi / 2.0, Eigen::Vector3d::UnitZ()));
  const CellModel cell =
      CellModel::FromXml(MjcfSource{.xml = xml, .file = analysis::BuiltinCellPath(), .assets = {}, .builtin = false},
                         CellModel::RobotInfo{"FANUC ARC Mate 100iC/12", "builtin"}, Eigen::Isometry3d::Identity(),
                         X_WB);
  EXPECT_THAT(cell.CollisionGeometry().unsupported, ::testing::HasSubstr("floor_bumps is a height field"));
  twin::CellSettings settings = OkSettings();
  settings.check_mode = CheckMode::kContinuous;
  const CheckReport report = CheckPlan(cell, SwingPlan(), settings, 100.0, nullptr);
  EXPECT_EQ(report.mode, CheckMode::kDiscrete);
  EXPECT_THAT(report.mode_fallback, ::testing::HasSubstr("floor_bumps"));
}

// A plane on a body an axis moves cannot reach the distance bounds: MuJoCo 2.2 refuses the model when it loads it
// (CollisionGeometry() demands planes are static).
TEST(CellSweepTest, APlaneOnAMovingBodyIsRefusedAtLoad) {
  std::ifstream in(analysis::BuiltinCellPath());
  std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string anchor = "<body name=\"link2\" pos=\"0.15 0 0.45\">";
  ASSERT_NE(xml.find(anchor), std::string::npos);
  xml.insert(xml.find(anchor) + anchor.size(), "\n<geom name=\"link2_plane\" type=\"plane\" size=\"0.1 0.1 0.01\"/>");
  const MjcfSource mjcf{.xml = xml, .file = analysis::BuiltinCellPath(), .assets = {}, .builtin = false};
  EXPECT_THROW(CellModel::FromXml(mjcf, CellModel::RobotInfo{"FANUC ARC Mate 100iC/12", "builtin"},
                                  Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity()),
               InputError);
}

TEST(CellSweepTest, PairsLeaveOutTheModelsExcludedBodies) {
  const CellModel cell = LoadCell(OkSettings());
  const CellCollisionGeometry geometry = cell.CollisionGeometry();
  auto has = [&](const std::string& b1, const std::string& b2) {
    for (const std::array<int, 2>& p : geometry.pairs) {
      const std::string& x = geometry.body[p[0]];
      const std::string& y = geometry.body[p[1]];
      if ((x == b1 && y == b2) || (x == b2 && y == b1)) return true;
    }
    return false;
  };
  EXPECT_FALSE(has("positioner_base", "tilt"));
  EXPECT_FALSE(has("positioner_base", "table"));
  EXPECT_FALSE(has("tilt", "substrate"));
  EXPECT_TRUE(has("robot_base", "tilt"));
  EXPECT_TRUE(has("robot_base", "table"));
  EXPECT_TRUE(has("link3", "positioner_base"));
}

TEST(CellSweepTest, TreeForwardKinematicsIsMujocos) {
  // The URDF mesh arm (fixed joints, meshes) and the built-in cell: the geometry's own tree against mj_kinematics.
  const fs::path robots = fs::path(WAAM_SOURCE_DIR) / "scenarios" / "cell" / "robots";
  twin::CellSettings urdf;
  urdf.robot_urdf = robots / "waam_kr16_support" / "urdf" / "kr16_2.urdf";
  urdf.robot_package_paths = {robots};
  for (const twin::CellSettings& settings : {OkSettings(), urdf}) {
    const CellModel cell = LoadCell(settings);
    const CellCollisionGeometry geometry = cell.CollisionGeometry();
    CellState state(cell);
    std::vector<Eigen::Isometry3d> mujoco, tree;
    std::srand(7);
    for (int k = 0; k < 50; ++k) {
      const planner::Joints8 q = planner::Joints8::Random() * kPi;
      state.SetJoints(q);
      state.ShapePoses(geometry, &mujoco);
      ShapePosesAt(geometry, q, &tree);
      ASSERT_EQ(tree.size(), mujoco.size());
      for (std::size_t i = 0; i < tree.size(); ++i) {
        EXPECT_LT((tree[i].translation() - mujoco[i].translation()).norm(), 1e-6) << geometry.body[i];
        EXPECT_LT((tree[i].linear() - mujoco[i].linear()).norm(), 1e-9) << geometry.body[i];
      }
    }
  }
}

}  // namespace
}  // namespace waam::twin
