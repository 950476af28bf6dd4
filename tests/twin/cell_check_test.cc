// Tests of the MuJoCo cell: the closed-form IK agrees with MuJoCo's forward kinematics, bad model files give clear
// errors, and the three planted faults (out of reach, joint past its limit, torch into the plate) are caught.
#include "models/core/numbers.h"
#include "analysis/cell_files.h"
#include "twin/cell/cell_check.h"

#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <thread>

#include <unistd.h>

#include <mujoco/mujoco.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/core/yaml_map.h"
#include "tests/twin/test_plans.h"
#include "twin/cell/cell_section.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {
namespace {
using analysis::LoadCell;
namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string ReadFileForTest(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::set<std::string> Kinds(const CheckReport& r) {
  std::set<std::string> kinds;
  for (const CheckViolation& v : r.violations) kinds.insert(std::string(NameOf(v.kind)));
  return kinds;
}

std::string Describe(const CheckReport& r) {
  std::string text;
  for (const CheckViolation& v : r.violations) {
    text += std::string(NameOf(v.kind)) + " " + v.joint + v.body1 + "/" + v.body2 + " at point " + std::to_string(v.point) + " value " +
            std::to_string(v.value) + " " + v.unit + "\n";
  }
  return text;
}

TEST(CellModelTest, ClosedFormIkReachesTheTcpInMujoco) {
  const twin::CellSettings settings;
  const CellModel model = LoadCell(settings);
  const planner::CellKinematics kin = PartKinematics(model, settings);
  CellState cell(model);
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 2000; ++trial) {
    // Random TCP poses around the positioner, torch tilted up to ~45 deg from vertical.
    const Eigen::Vector3d p_W = kin.X_WB.translation() + Eigen::Vector3d(250 * u(rng), 250 * u(rng), 600 + 150 * u(rng));
    const Eigen::Vector3d dir = Eigen::Vector3d(0.7 * u(rng), 0.7 * u(rng), 1.0).normalized();
    const Eigen::Isometry3d X_WT = planner::TorchPose(kin, p_W, dir);
    const Eigen::Isometry3d X_RF = kin.X_WR.inverse() * X_WT * kin.X_FT.inverse();
    const planner::IkSolutions ik = planner::SolveIk(kin.arm, X_RF, nullptr);
    for (int i = 0; i < ik.count; ++i) {
      planner::Joints8 q = planner::Joints8::Zero();
      q.head<6>() = ik.solutions[i].q;
      cell.SetJoints(q);
      const Eigen::Isometry3d X = cell.TcpPose();
      const double err = (X.translation() - X_WT.translation()).norm() + 1000.0 * (X.linear() - X_WT.linear()).norm();
      worst = std::max(worst, err);
      ++checked;
    }
  }
  EXPECT_GT(checked, 2000);
  EXPECT_LT(worst, 1e-6) << "every IK branch must put MuJoCo's TCP site on the target pose (mm)";
}

TEST(CellModelTest, ModelKinematicsMatchThePublishedArm) {
  const CellModel cell = analysis::LoadCellModel({});
  const planner::CellKinematics kin = cell.kinematics();
  const planner::OpwArm ref = planner::OpwArm::ArcMate100iC12();
  EXPECT_NEAR(kin.arm.a1, ref.a1, 1e-9);
  EXPECT_NEAR(kin.arm.a2, ref.a2, 1e-9);
  EXPECT_NEAR(kin.arm.c1, ref.c1, 1e-9);
  EXPECT_NEAR(kin.arm.c2, ref.c2, 1e-9);
  EXPECT_NEAR(kin.arm.c3, ref.c3, 1e-9);
  EXPECT_NEAR(kin.arm.c4, ref.c4, 1e-9);
  EXPECT_LT((kin.arm.lower - ref.lower).norm(), 1e-9);
  EXPECT_LT((kin.arm.max_speed - ref.max_speed).norm(), 1e-9);
  EXPECT_NEAR(kin.positioner.tilt_upper - kin.positioner.tilt_lower, 140.0 * kPi / 180.0, 1e-9);
  EXPECT_NEAR(kin.positioner.rotation_upper - kin.positioner.rotation_lower, 480.0 * kPi / 180.0, 1e-9);
}

class BadModelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("waam_cell_model_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string ErrorOf(const std::string& xml) {
    const fs::path file = dir_ / "cell.xml";
    std::ofstream(file) << xml;
    try {
      twin::CellSettings settings;
      settings.mjcf = file;
      LoadCell(settings);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "expected an InputError for:\n" << xml;
    return "";
  }
  fs::path dir_;
};

TEST_F(BadModelTest, BrokenXmlIsAnErrorNotAnExit) {
  const std::string message = ErrorOf("<mujoco><worldbody><body name='a'></worldbody></mujoco>");
  EXPECT_THAT(message, HasSubstr("cell.xml"));
  EXPECT_THAT(message, HasSubstr("cannot load"));
}

TEST_F(BadModelTest, MissingJointIsNamed) {
  std::string xml = ReadFileForTest(analysis::BuiltinCellPath());
  xml.replace(xml.find("name=\"j3\""), 9, "name=\"jx\"");
  EXPECT_THAT(ErrorOf(xml), HasSubstr("no joint named 'j3'"));
}

// A user's arm that is not of the OPW kind: a 20 mm lateral offset in the wrist.
class NumericIkTest : public BadModelTest {
 protected:
  fs::path WristOffsetModel() {
    std::string xml = ReadFileForTest(analysis::BuiltinCellPath());
    xml.replace(xml.find("<body name=\"link6\" pos=\"0.1 0 0\">"), 33, "<body name=\"link6\" pos=\"0.1 0.02 0\">");
    const fs::path file = dir_ / "offset_wrist.xml";
    std::ofstream(file) << xml;
    return file;
  }
};

TEST_F(NumericIkTest, NonOpwArmFallsBackToNumericalIk) {
  twin::CellSettings settings;
  settings.mjcf = WristOffsetModel();
  const CellModel model = LoadCell(settings);
  const planner::CellKinematics kin = PartKinematics(model, settings);
  EXPECT_FALSE(model.closed_form());
  CellState cell(model);
  ASSERT_TRUE(static_cast<bool>(kin.numeric_ik));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int converged = 0;
  for (int trial = 0; trial < 50; ++trial) {
    planner::Joints8 q = planner::Joints8::Zero();
    q << 0.5 * u(rng), 0.3 + 0.3 * u(rng), 0.2 * u(rng), 0.5 * u(rng), -1.3 + 0.4 * u(rng), 0.5 * u(rng), 0, 0;
    cell.SetJoints(q);
    const Eigen::Isometry3d X_WT = cell.TcpPose();
    const Eigen::Isometry3d X_RF = kin.X_WR.inverse() * X_WT * kin.X_FT.inverse();
    const planner::Joints6 seed = q.head<6>() + planner::Joints6::Constant(0.1);
    planner::Joints6 sol;
    double residual = 0.0;
    if (!kin.numeric_ik(X_RF, seed, &sol, &residual)) continue;
    ++converged;
    planner::Joints8 q2 = q;
    q2.head<6>() = sol;
    cell.SetJoints(q2);
    EXPECT_LT((cell.TcpPose().translation() - X_WT.translation()).norm(), 1e-5) << "trial " << trial;
  }
  EXPECT_EQ(converged, 50) << "from a seed 0.1 rad away the numerical IK must converge";
}

TEST_F(NumericIkTest, OneModelServesTwoThreadsAtOnce) {
  // The model is shared; each thread has its own CellState and the IK has its own data per call: two threads
  // solving and checking different poses at once get exactly what one thread gets.
  twin::CellSettings settings;
  settings.mjcf = WristOffsetModel();
  const CellModel model = LoadCell(settings);
  const planner::CellKinematics kin = PartKinematics(model, settings);
  ASSERT_TRUE(static_cast<bool>(kin.numeric_ik));
  auto solve_all = [&](int first, std::vector<double>* out) {
    CellState state(model);
    std::mt19937_64 rng(first);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int trial = 0; trial < 40; ++trial) {
      planner::Joints8 q = planner::Joints8::Zero();
      q << 0.5 * u(rng), 0.3 + 0.3 * u(rng), 0.2 * u(rng), 0.5 * u(rng), -1.3 + 0.4 * u(rng), 0.5 * u(rng), 0, 0;
      state.SetJoints(q);
      const Eigen::Isometry3d X_RF = kin.X_WR.inverse() * state.TcpPose() * kin.X_FT.inverse();
      planner::Joints6 sol;
      double residual = 0.0;
      kin.numeric_ik(X_RF, q.head<6>() + planner::Joints6::Constant(0.1), &sol, &residual);
      for (int j = 0; j < 6; ++j) out->push_back(sol[j]);
      std::vector<CellContact> contacts;
      double clearance = 0.0;
      state.Collide(0.0, &contacts, &clearance);
      out->push_back(clearance);
    }
  };
  std::vector<double> serial_a, serial_b, threaded_a, threaded_b;
  solve_all(1, &serial_a);
  solve_all(2, &serial_b);
  std::thread a(solve_all, 1, &threaded_a);
  std::thread b(solve_all, 2, &threaded_b);
  a.join();
  b.join();
  EXPECT_EQ(threaded_a, serial_a);
  EXPECT_EQ(threaded_b, serial_b);
}

TEST_F(NumericIkTest, WellPlacedWallPassesWithNumericalIk) {
  twin::CellSettings settings;
  settings.mjcf = WristOffsetModel();
  const CheckReport r =
      CheckPlan(LoadCell(settings), testing::RectangleWall(4, 80.0, 40.0, 2.0, 400.0 / 60.0), settings, 100.0, nullptr);
  EXPECT_EQ(r.ik, "numerical");
  EXPECT_TRUE(r.ok) << Describe(r);
}

TEST_F(NumericIkTest, NumericalIkFailureIsReportedAsUnreachable) {
  twin::CellSettings far;
  far.mjcf = WristOffsetModel();
  far.robot_base_mm = {-1500.0, 0.0, 0.0};
  // A small square: every point fails the numerical IK at its full iteration count, in the fixed motion and in each
  // spin the resolver tries, so the points are kept few.
  const CheckReport r =
      CheckPlan(LoadCell(far), testing::RectangleWall(1, 20.0, 10.0, 2.0, 400.0 / 60.0), far, 100.0, nullptr);
  EXPECT_EQ(Kinds(r), std::set<std::string>{"unreachable"}) << Describe(r);
  EXPECT_EQ(r.violations.front().unit, "ik_residual_mm");
}

TEST_F(BadModelTest, MujocoRuntimeErrorThrowsInsteadOfExiting) {
  const CellModel cell = analysis::LoadCellModel({});  // installs the handlers
  try {
    mju_error("simulated engine failure");
    ADD_FAILURE() << "mju_error must throw, not return or exit";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("simulated engine failure"));
  }
}

TEST_F(BadModelTest, MissingFileIsNamed) {
  try {
    const CellModel cell = analysis::LoadCellModel(dir_ / "nothere.xml");
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("nothere.xml"));
  }
}

// The planted-fault scenarios of scenarios/cell/, checked on a hand-built wall of their part's footprint.
class PlantedFaultTest : public ::testing::Test {
 protected:
  static twin::CellSettings Settings(const std::string& name) {
    const fs::path file = fs::path(WAAM_SOURCE_DIR) / "scenarios" / "cell" / (name + ".yaml");
    YamlMap top = YamlMap(LoadYamlFile(file.string()), "", file.string());
    return ParseCellSection(top);
  }
  CheckReport Check(const twin::CellSettings& settings) {
    return CheckPlan(LoadCell(settings), testing::RectangleWall(10, 100.0, 60.0, 1.5, 400.0 / 60.0), settings, 100.0, nullptr);
  }
};

TEST_F(PlantedFaultTest, WellPlacedCellPasses) {
  const CheckReport r = Check(Settings("cell_ok"));
  EXPECT_TRUE(r.ok) << Describe(r);
  EXPECT_EQ(r.points, 50u);
  EXPECT_GT(r.samples, 10u * 320u) << "segments are checked every step_mm (1 mm)";
  EXPECT_GT(r.min_joint_margin_deg, 2.0);
  EXPECT_GT(r.max_joint_speed_ratio, 0.0);
  EXPECT_LT(r.max_joint_speed_ratio, 1.0);
  EXPECT_GT(r.min_j5_deg, 5.0);
}

TEST_F(PlantedFaultTest, OutOfReachIsUnreachableOnly) {
  const CheckReport r = Check(Settings("cell_out_of_reach"));
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(Kinds(r), std::set<std::string>{"unreachable"}) << Describe(r);
  EXPECT_GT(r.violations.front().value, 0.0) << "reports how far out of reach, mm";
}

TEST_F(PlantedFaultTest, PositionerBehindTheArmDrivesJ1PastItsLimit) {
  const CheckReport r = Check(Settings("cell_joint_limit"));
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(Kinds(r), std::set<std::string>{"joint_limit"}) << Describe(r);
  for (const CheckViolation& v : r.violations) EXPECT_EQ(v.joint, "j1") << Describe(r);
  EXPECT_LT(r.min_joint_margin_deg, 0.0);
}

TEST_F(PlantedFaultTest, PartBelowThePlateDrivesTheTorchIntoTheSubstrate) {
  const CheckReport r = Check(Settings("cell_torch_into_plate"));
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(Kinds(r), std::set<std::string>{"collision"}) << Describe(r);
  for (const CheckViolation& v : r.violations) {
    EXPECT_EQ(v.body1, "substrate") << Describe(r);
    EXPECT_EQ(v.body2, "torch") << Describe(r);
  }
}

TEST_F(PlantedFaultTest, JointMarginIsAViolationBeforeTheLimit) {
  // Arm turned so that j1 works at 167 +- 3 deg: inside its +-170 deg range but closer than the 2 deg margin.
  twin::CellSettings s = Settings("cell_ok");
  s.robot_yaw_deg = -167.0;
  const CheckReport r = Check(s);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(Kinds(r), std::set<std::string>{"joint_limit"}) << Describe(r);
  EXPECT_GT(r.min_joint_margin_deg, 0.0) << "no joint passes its limit";
  EXPECT_LT(r.min_joint_margin_deg, 2.0);
  EXPECT_EQ(r.min_margin_joint, "j1");
}

TEST_F(PlantedFaultTest, WristNearItsSingularityIsReported) {
  // The welding posture keeps |j5| near 80 deg; demanding 85 deg of distance flags it, and nothing else.
  twin::CellSettings s = Settings("cell_ok");
  s.singularity_deg = 85.0;
  const CheckReport r = Check(s);
  EXPECT_EQ(Kinds(r), std::set<std::string>{"singularity"}) << Describe(r);
  EXPECT_LT(r.min_j5_deg, 85.0);
  for (const CheckViolation& v : r.violations) EXPECT_EQ(v.joint, "j5");
}

TEST_F(PlantedFaultTest, TravelSpeedBeyondTheAxesIsAJointSpeedViolation) {
  // Welding a small square at 3 m/s: the arm cannot follow; travel moves are slowed, weld moves are not.
  const twin::CellSettings settings = Settings("cell_ok");
  const CheckReport r =
      CheckPlan(LoadCell(settings), testing::RectangleWall(2, 20.0, 20.0, 1.5, 3000.0), settings, 100.0, nullptr);
  EXPECT_EQ(Kinds(r), std::set<std::string>{"joint_speed"}) << Describe(r);
  EXPECT_GT(r.max_joint_speed_ratio, 1.0);
}

TEST_F(PlantedFaultTest, TorchAgainstTheDepositedWallIsACollisionWithThePart) {
  // Layers whose tool direction leans 75 deg sideways while the build direction stays vertical: the nozzle dips
  // into the layers laid before.
  planner::Plan plan = testing::RectangleWall(10, 100.0, 60.0, 1.5, 400.0 / 60.0);
  for (planner::LayerPath& layer : plan.layers) {
    for (planner::PathPoint& p : layer.points) p.tool_dir_P = Eigen::Vector3d(std::sin(1.3), 0.0, std::cos(1.3));
  }
  const CheckReport r = CheckPlan(LoadCell(Settings("cell_ok")), plan, Settings("cell_ok"), 100.0, nullptr);
  bool part_hit = false;
  for (const CheckViolation& v : r.violations) part_hit |= (v.kind == ViolationKind::kCollision && v.body1 == "part");
  EXPECT_TRUE(part_hit) << "a torch leaning 75 deg must hit the wall it just built\n" << Describe(r);
}

TEST_F(PlantedFaultTest, SkippedCollisionChecksMissNothing) {
  // A pass that ramps from 40 mm above the plate to 25 mm below it: the check (which skips MuJoCo detections while
  // the clearance allows) must flag exactly the samples a detection at every sample flags.
  planner::Plan plan;
  planner::LayerPath layer;
  for (int i = 0; i <= 40; ++i) {
    planner::PathPoint p;
    p.p_P = Eigen::Vector3d(-100.0 + 5.0 * i, 0.0, 40.0 - 65.0 * i / 40.0);
    p.bead_width_mm = 6.0;
    p.bead_height_mm = 1.5;
    p.speed_mm_s = 5.0;
    p.weld = i > 0;
    layer.points.push_back(p);
  }
  plan.layers.push_back(layer);
  twin::CellSettings settings = Settings("cell_ok");
  settings.part_collision = false;
  const CellModel model = LoadCell(settings);
  const CheckReport r = CheckPlan(model, plan, settings, 100.0, nullptr);
  int flagged = 0;
  for (const CheckViolation& v : r.violations) {
    if (v.kind == ViolationKind::kCollision) flagged += v.samples;
  }
  int brute = 0;
  std::vector<CellContact> contacts;
  CellState cell(model);
  for (const planner::CellSample& s : r.motion) {
    cell.SetJoints(s.q);
    contacts.clear();
    if (cell.Collide(settings.collision_tolerance_mm, &contacts, nullptr) > 0) ++brute;
  }
  EXPECT_GT(brute, 20) << "the ramp must end inside the plate";
  EXPECT_EQ(flagged, brute) << Describe(r);
}

TEST_F(PlantedFaultTest, TiltedBuildDirectionIsTurnedUpByThePositioner) {
  // A wall whose layers grow along a direction 30 deg from the plate normal: the positioner tilts by 30 deg and the
  // torch stays vertical (neutral welding position).
  planner::Plan plan = testing::RectangleWall(5, 60.0, 40.0, 1.5, 400.0 / 60.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(30.0 * kPi / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (planner::LayerPath& layer : plan.layers) {
    layer.build_dir_P = R * Eigen::Vector3d::UnitZ();
    for (planner::PathPoint& p : layer.points) {
      p.p_P = R * p.p_P + Eigen::Vector3d(0.0, 0.0, 20.0);
      p.tool_dir_P = layer.build_dir_P;
    }
  }
  const CheckReport r = CheckPlan(LoadCell(Settings("cell_ok")), plan, Settings("cell_ok"), 100.0, nullptr);
  EXPECT_TRUE(r.ok) << Describe(r);
  EXPECT_NEAR(std::abs(r.motion.back().q[6]) * 180.0 / kPi, 30.0, 1e-6) << "positioner tilt";
  EXPECT_LT(r.max_torch_tilt_deg, 1e-6) << "the torch stays vertical";
  EXPECT_EQ(r.positioner_limit_layers, 0);
}

}  // namespace
}  // namespace waam::twin
