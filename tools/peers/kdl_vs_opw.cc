// tools/peers.sh: KDL's numerical inverse kinematics against waam's closed form on the same arm, built by the script
// against Debian's KDL, not part of the project build: the FANUC ARC Mate 100iC/12 of planner/kinematics/opw_arm.h, or
// with a URDF path the arm of that URDF (base_link -> tool0, six revolute joints): KDL's chain built from the URDF's
// joints here (kdl_parser is not in Debian), waam's OPW parameters read off the same chain's axes at the zero pose
// (planner::OpwFromAxes, as the cell does for a URDF arm) and checked against KDL's forward kinematics.
// Both solve the flange poses of the same seeded random joint vectors from the same seeds (the target's joints
// moved by up to 0.1 rad, as along a path); each answer is checked by waam's forward kinematics: solved when the
// position error plus 1000 mm x the rotation error (rad) is below 1e-3 mm, far below a robot's repeatability. waam is
// timed twice: every branch then PickNearest, and SolveIkNearest from the seed's branch (as along a path).
// Usage: kdl_vs_opw [poses] [urdf]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>

#include "planner/kinematics/opw_arm.h"

namespace {

using waam::planner::Joints6;
using waam::planner::OpwArm;

// Pose error of flange pose b against a: position (mm) plus rotation angle (rad) times 1000 mm.
double PoseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::AngleAxisd d(a.linear().transpose() * b.linear());
  return (a.translation() - b.translation()).norm() + 1000.0 * std::abs(d.angle());
}

KDL::Vector Metres(const Eigen::Vector3d& p_mm) { return KDL::Vector(p_mm.x(), p_mm.y(), p_mm.z()) / 1000.0; }

// The arm as a KDL chain (metres): joint axes and zero-pose positions from waam's own kinematics (opw_arm.h: j1 +z,
// j2 +y, j3 -y, j4 -x, j5 -y, j6 -x; upper arm vertical and forearm along +x at q = 0).
KDL::Chain ChainOf(const OpwArm& arm) {
  const Eigen::Vector3d j2(arm.a1, 0.0, arm.c1), j3(arm.a1, 0.0, arm.c1 + arm.c2);
  const Eigen::Vector3d wrist = waam::planner::WristCentre(arm, Joints6::Zero());
  const Eigen::Isometry3d flange = waam::planner::ForwardKinematics(arm, Joints6::Zero());
  const Eigen::Matrix3d R = flange.linear();
  const KDL::Rotation R_tip(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2));
  auto rot = [](double x, double y, double z) {
    return KDL::Joint(KDL::Vector::Zero(), KDL::Vector(x, y, z), KDL::Joint::RotAxis);
  };
  KDL::Chain chain;
  chain.addSegment(KDL::Segment(rot(0, 0, 1), KDL::Frame(Metres(j2))));
  chain.addSegment(KDL::Segment(rot(0, 1, 0), KDL::Frame(Metres(j3 - j2))));
  chain.addSegment(KDL::Segment(rot(0, -1, 0), KDL::Frame(Metres(wrist - j3))));
  chain.addSegment(KDL::Segment(rot(-1, 0, 0), KDL::Frame::Identity()));
  chain.addSegment(KDL::Segment(rot(0, -1, 0), KDL::Frame::Identity()));
  chain.addSegment(KDL::Segment(rot(-1, 0, 0), KDL::Frame(R_tip, Metres(flange.translation() - wrist))));
  return chain;
}

// Three numbers of a URDF attribute (absent: zeros).
KDL::Vector Triple(const tinyxml2::XMLElement* e, const char* attribute) {
  double v[3] = {0.0, 0.0, 0.0};
  if (e && e->Attribute(attribute)) {
    std::istringstream in(e->Attribute(attribute));
    in >> v[0] >> v[1] >> v[2];
  }
  return KDL::Vector(v[0], v[1], v[2]);
}

[[noreturn]] void Fail(const std::string& why) {
  std::fprintf(stderr, "kdl_vs_opw: %s\n", why.c_str());
  std::exit(1);
}

// The chain base_link -> tool0 of a URDF as kdl_parser builds it: per joint a segment whose joint sits at the
// joint's origin with its axis turned into the parent's frame, and whose tip is that origin. Limits into `lower`,
// `upper` (rad).
KDL::Chain ChainOfUrdf(const char* path, Joints6* lower, Joints6* upper) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(path) != tinyxml2::XML_SUCCESS) Fail(std::string("cannot read ") + path);
  std::vector<const tinyxml2::XMLElement*> joints;
  for (auto* j = doc.RootElement()->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) joints.push_back(j);
  // Walk back from tool0 to base_link.
  std::vector<const tinyxml2::XMLElement*> path_joints;
  for (std::string link = "tool0"; link != "base_link";) {
    const tinyxml2::XMLElement* found = nullptr;
    for (auto* j : joints) {
      if (link == j->FirstChildElement("child")->Attribute("link")) found = j;
    }
    if (!found) Fail("no joint leads to link " + link);
    path_joints.insert(path_joints.begin(), found);
    link = found->FirstChildElement("parent")->Attribute("link");
  }
  KDL::Chain chain;
  int k = 0;
  for (auto* j : path_joints) {
    const auto* origin = j->FirstChildElement("origin");
    const KDL::Vector rpy = Triple(origin, "rpy");
    const KDL::Frame F(KDL::Rotation::RPY(rpy.x(), rpy.y(), rpy.z()), Triple(origin, "xyz"));
    if (std::strcmp(j->Attribute("type"), "fixed") == 0) {
      chain.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::None), F));
      continue;
    }
    if (k == 6) Fail("more than six moving joints");
    const auto* limit = j->FirstChildElement("limit");
    (*lower)[k] = limit->DoubleAttribute("lower");
    (*upper)[k] = limit->DoubleAttribute("upper");
    ++k;
    const KDL::Vector axis = Triple(j->FirstChildElement("axis"), "xyz");
    chain.addSegment(KDL::Segment(KDL::Joint(j->Attribute("name"), F.p, F.M * axis, KDL::Joint::RotAxis), F));
  }
  if (k != 6) Fail("not six moving joints");
  return chain;
}

Eigen::Isometry3d FromKdl(const KDL::Frame& f) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) X.linear()(r, c) = f.M(r, c);
    X.translation()(r) = 1000.0 * f.p(r);
  }
  return X;
}

// waam's OPW arm of a KDL chain: the axes at q = 0 (mm, in the chain's base frame) read by OpwFromAxes.
OpwArm ArmOfChain(const KDL::Chain& chain, const Joints6& lower, const Joints6& upper) {
  waam::planner::ArmAxes axes;
  KDL::Frame X = KDL::Frame::Identity();
  int k = 0;
  for (unsigned s = 0; s < chain.getNrOfSegments(); ++s) {
    const KDL::Segment& seg = chain.getSegment(s);
    if (seg.getJoint().getType() != KDL::Joint::None) {
      const KDL::Vector p = X * seg.getJoint().JointOrigin(), a = X.M * seg.getJoint().JointAxis();
      axes.point_R[k] = 1000.0 * Eigen::Vector3d(p.x(), p.y(), p.z());
      axes.axis_R[k] = Eigen::Vector3d(a.x(), a.y(), a.z()).normalized();
      ++k;
    }
    X = X * seg.pose(0.0);
  }
  axes.X_RF0 = FromKdl(X);
  std::string why;
  std::optional<OpwArm> arm = waam::planner::OpwFromAxes(axes, &why);
  if (!arm) Fail("the URDF's arm is not of the OPW kind: " + why);
  arm->lower = lower;
  arm->upper = upper;
  return *arm;
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 20000;
  Joints6 lower, upper;
  const KDL::Chain chain = argc > 2 ? ChainOfUrdf(argv[2], &lower, &upper) : ChainOf(OpwArm::ArcMate100iC12());
  const OpwArm arm = argc > 2 ? ArmOfChain(chain, lower, upper) : OpwArm::ArcMate100iC12();
  std::printf("kdl_vs_opw: arm %s\n", argc > 2 ? argv[2] : "FANUC ARC Mate 100iC/12 (built in)");
  KDL::ChainFkSolverPos_recursive fk(chain);
  KDL::ChainIkSolverPos_LMA ik(chain, 1e-12, 500, 1e-15);

  std::mt19937_64 rng(7);
  std::vector<Joints6> targets(n), seeds(n);
  std::vector<Eigen::Isometry3d> poses(n);
  double chain_error = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < 6; ++j) {
      // Inside the limits, away from them by 0.2 rad, so the seed stays inside too.
      const double lo = std::max(arm.lower[j], -2.5) + 0.2, hi = std::min(arm.upper[j], 2.5) - 0.2;
      targets[i][j] = std::uniform_real_distribution<double>(lo, hi)(rng);
      seeds[i][j] = targets[i][j] + std::uniform_real_distribution<double>(-0.1, 0.1)(rng);
    }
    poses[i] = waam::planner::ForwardKinematics(arm, targets[i]);
    KDL::JntArray q(6);
    for (int j = 0; j < 6; ++j) q(j) = targets[i][j];
    KDL::Frame f;
    fk.JntToCart(q, f);
    chain_error = std::max(chain_error, PoseError(poses[i], FromKdl(f)));
  }
  std::printf("kdl_vs_opw: %d poses; KDL chain vs waam forward kinematics: largest difference %.2e mm\n", n,
              chain_error);

  using Clock = std::chrono::steady_clock;
  int opw_ok = 0, kdl_ok = 0;
  double opw_worst = 0.0, kdl_worst = 0.0;
  auto t0 = Clock::now();
  std::vector<Joints6> opw_q(n);
  for (int i = 0; i < n; ++i) {
    const waam::planner::IkSolutions all = waam::planner::SolveIk(arm, poses[i], &seeds[i]);
    const int k = waam::planner::PickNearest(arm, all, &seeds[i]);
    opw_q[i] = k >= 0 ? all.solutions[k].q : seeds[i];
  }
  const double opw_s = std::chrono::duration<double>(Clock::now() - t0).count();
  // Along a path the previous sample's branch is known: SolveIkNearest solves that one alone where it decides.
  std::vector<int> seed_branch(n);
  for (int i = 0; i < n; ++i) {
    const waam::planner::IkSolutions own = waam::planner::SolveIk(arm, waam::planner::ForwardKinematics(arm, seeds[i]), &seeds[i]);
    const int k = waam::planner::PickNearest(arm, own, &seeds[i]);
    seed_branch[i] = k >= 0 ? own.solutions[k].opw_branch : -1;
  }
  int single = 0, same = 0;
  t0 = Clock::now();
  std::vector<Joints6> one_q(n);
  for (int i = 0; i < n; ++i) {
    const waam::planner::IkNearest one = waam::planner::SolveIkNearest(arm, poses[i], seeds[i], seed_branch[i]);
    one_q[i] = one.reachable ? one.solution.q : seeds[i];
    single += !one.all_branches;
  }
  const double one_s = std::chrono::duration<double>(Clock::now() - t0).count();
  for (int i = 0; i < n; ++i) same += one_q[i] == opw_q[i];
  t0 = Clock::now();
  std::vector<Joints6> kdl_q(n);
  for (int i = 0; i < n; ++i) {
    KDL::JntArray seed(6), out(6);
    for (int j = 0; j < 6; ++j) seed(j) = seeds[i][j];
    KDL::Frame target;
    target.p = Metres(poses[i].translation());
    const Eigen::Matrix3d& R = poses[i].linear();
    target.M = KDL::Rotation(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2));
    const int status = ik.CartToJnt(seed, target, out);
    for (int j = 0; j < 6; ++j) kdl_q[i][j] = status >= 0 ? out(j) : seeds[i][j];
  }
  const double kdl_s = std::chrono::duration<double>(Clock::now() - t0).count();
  // Both checked the same way: waam's forward kinematics of the answer against the pose.
  for (int i = 0; i < n; ++i) {
    const double e_opw = PoseError(poses[i], waam::planner::ForwardKinematics(arm, opw_q[i]));
    const double e_kdl = PoseError(poses[i], waam::planner::ForwardKinematics(arm, kdl_q[i]));
    opw_ok += e_opw < 1e-3;
    kdl_ok += e_kdl < 1e-3;
    opw_worst = std::max(opw_worst, e_opw);
    kdl_worst = std::max(kdl_worst, e_kdl);
  }
  std::printf("kdl_vs_opw: waam closed form   %8.3f us/pose  solved %d/%d (worst %.1e)\n", 1e6 * opw_s / n, opw_ok,
              n, opw_worst);
  std::printf("kdl_vs_opw: KDL LMA (numerical) %8.3f us/pose  solved %d/%d (worst %.1e)\n", 1e6 * kdl_s / n, kdl_ok,
              n, kdl_worst);
  std::printf("kdl_vs_opw: waam seed's branch   %8.3f us/pose  %d/%d by one branch, %d/%d the same answer\n",
              1e6 * one_s / n, single, n, same, n);
  std::printf("ratio kdl/waam ik %.1f (all branches), %.1f (seed's branch)\n", kdl_s / opw_s, kdl_s / one_s);
  return 0;
}
