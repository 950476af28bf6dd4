// MuJoCo adapter of the cell: the only file that sees mjModel/mjData. MuJoCo errors become InputError, never exit().
#include "twin/cell/mujoco_cell.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <string>

#include <mujoco/mujoco.h>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "twin/cell/mujoco_cell_internal.h"

namespace waam::twin {
namespace fs = std::filesystem;
using planner::Joints8;

namespace {

constexpr double kMm = 1000.0;  // model metres -> mm
const char* const kArmJoints[6] = {"j1", "j2", "j3", "j4", "j5", "j6"};

// MuJoCo calls this instead of exit(): unwinding through MuJoCo's C frames is fine on gcc/x86-64 (unwind tables).
void ThrowOnMujocoError(const char* message) { throw InputError(std::string("MuJoCo error: ") + message); }
void IgnoreMujocoWarning(const char*) {}

void InstallMujocoHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = ThrowOnMujocoError;
    mju_user_warning = IgnoreMujocoWarning;
  });
}

Eigen::Isometry3d Pose(const mjtNum* pos, const mjtNum* mat) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(pos[0], pos[1], pos[2]) * kMm;
  X.linear() = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(mat);
  return X;
}

// The MJCF text and its assets in a MuJoCo virtual file system, which mj_loadXML reads instead of the disk.
class Vfs {
 public:
  explicit Vfs(const MjcfSource& mjcf) : vfs_(std::make_unique<mjVFS>()) {
    mj_defaultVFS(vfs_.get());
    WAAM_THROW_UNLESS(mjcf.assets.size() + 1 < mjMAXVFS, mjcf.file.string() << ": the cell model names "
                                                                              << mjcf.assets.size()
                                                                              << " files, more than MuJoCo's "
                                                                              << mjMAXVFS - 2);
    const std::string base = mjcf.file.filename().string();
    main_ = base.empty() || base.size() >= mjMAXVFSNAME ? "waam_cell.xml" : base;
    Add(main_, mjcf.xml, mjcf.file);
    for (const auto& [name, bytes] : mjcf.assets) Add(name, bytes, mjcf.file);
  }
  ~Vfs() { mj_deleteVFS(vfs_.get()); }
  Vfs(const Vfs&) = delete;
  Vfs& operator=(const Vfs&) = delete;
  const mjVFS* get() const { return vfs_.get(); }
  const std::string& main() const { return main_; }

 private:
  void Add(const std::string& name, const std::string& bytes, const fs::path& model) {
    const std::string base = fs::path(name).filename().string();
    WAAM_THROW_UNLESS(!base.empty() && base.size() < mjMAXVFSNAME,
                      model.string() << ": the cell model names a file '" << name << "' MuJoCo cannot hold");
    // MuJoCo's VFS holds no empty file: an empty asset becomes one zero byte, which MuJoCo then refuses to read.
    const int size = std::max<int>(1, static_cast<int>(bytes.size()));
    const int added = mj_makeEmptyFileVFS(vfs_.get(), base.c_str(), size);
    WAAM_THROW_UNLESS(added != 2, model.string() << ": two files the cell model names are called '" << base
                                                 << "' (MuJoCo finds files by name, without their folders, in any "
                                                    "case): rename one");
    WAAM_DEMAND(added == 0);
    std::memcpy(vfs_->filedata[vfs_->nfile - 1], bytes.data(), bytes.size());
  }
  std::unique_ptr<mjVFS> vfs_;
  std::string main_;
};

// Compiles and checks the model (the constructor's first half; placing the bases and the kinematics follow).
// `impl` owns the model; the returned pointer is the only one that may edit it, while BuildModel builds it.
mjModel* LoadModel(const MjcfSource& mjcf, CellModel::Impl* impl) {
  InstallMujocoHandlers();
  impl->file = mjcf.file;
  const fs::path& file = impl->file;
  char error[1024] = "";
  const Vfs vfs(mjcf);
  mjModel* m = mj_loadXML(vfs.main().c_str(), vfs.get(), error, sizeof(error));
  impl->m = m;
  if (m == nullptr) {
    // MuJoCo's XML errors span several lines ("XML parse error 14:\nError=... Line number=1: ..."): join them so
    // the CLI prints the one line the bad-input contract promises, with the line number MuJoCo reports.
    std::string message;
    for (const char* c = error; *c != '\0'; ++c) {
      const bool space = *c == '\n' || *c == '\r' || *c == ' ' || *c == '\t';
      if (!space) {
        message.push_back(*c);
      } else if (!message.empty() && message.back() != ' ') {
        message.push_back(' ');
      }
    }
    while (!message.empty() && message.back() == ' ') message.pop_back();
    WAAM_THROW(file.string() << ": MuJoCo cannot load the cell model: " << message);
  }

  auto require = [&](int type, const char* name, const char* what) {
    const int id = mj_name2id(m, type, name);
    WAAM_THROW_UNLESS(id >= 0, file.string() << ": the cell model has no " << what << " named '" << name
                                             << "' (see docs/SCENARIOS.md, 'Describing your own cell')");
    return id;
  };
  const char* const names[8] = {"j1", "j2", "j3", "j4", "j5", "j6", "pos_tilt", "pos_rot"};
  // The positioner's joints say its type: both (tilt_rotate), pos_rot alone (turntable) or none.
  const bool has_tilt = mj_name2id(m, mjOBJ_JOINT, "pos_tilt") >= 0;
  const bool has_rot = mj_name2id(m, mjOBJ_JOINT, "pos_rot") >= 0;
  WAAM_THROW_UNLESS(has_rot || !has_tilt, file.string() << ": the cell model has a joint 'pos_tilt' but no 'pos_rot' "
                                                           "(a positioner is tilt_rotate, turntable or none)");
  impl->positioner_type = has_tilt ? planner::PositionerType::kTiltRotate
                                   : (has_rot ? planner::PositionerType::kTurntable : planner::PositionerType::kNone);
  for (int j = 0; j < 8; ++j) {
    if (!planner::HasAxis(impl->positioner_type, j)) {
      impl->jnt[j] = impl->qadr[j] = -1;
      continue;
    }
    const int id = require(mjOBJ_JOINT, names[j], "joint");
    WAAM_THROW_UNLESS(m->jnt_type[id] == mjJNT_HINGE && m->jnt_limited[id],
                      file.string() << ": joint '" << names[j] << "' must be a limited hinge");
    impl->jnt[j] = id;
    impl->qadr[j] = m->jnt_qposadr[id];
  }
  impl->robot_base = require(mjOBJ_BODY, "robot_base", "body");
  impl->positioner_base = require(mjOBJ_BODY, "positioner_base", "body");
  impl->flange = require(mjOBJ_BODY, "link6", "body");
  impl->tcp = require(mjOBJ_SITE, "tcp", "site");
  impl->part_origin = require(mjOBJ_SITE, "part_origin", "site");
  impl->nozzle = require(mjOBJ_GEOM, "nozzle", "geom");
  impl->speeds = require(mjOBJ_NUMERIC, "max_speed_deg_s", "custom numeric");
  WAAM_THROW_UNLESS(m->numeric_size[impl->speeds] == 8,
                    file.string() << ": custom numeric 'max_speed_deg_s' must have 8 values (j1..j6, pos_tilt, "
                                     "pos_rot), has " << m->numeric_size[impl->speeds]);
  WAAM_THROW_UNLESS(m->geom_type[impl->nozzle] == mjGEOM_CAPSULE, file.string() << ": geom 'nozzle' must be a capsule");
  WAAM_THROW_UNLESS(m->body_parentid[impl->robot_base] == 0 && m->body_parentid[impl->positioner_base] == 0,
                    file.string() << ": bodies 'robot_base' and 'positioner_base' must be children of the world");
  // Contacts are reported up to kClearanceMarginMm apart, which gives the clearance used to skip checks.
  for (int g = 0; g < m->ngeom; ++g) m->geom_margin[g] = CellModel::kClearanceMarginMm / kMm;
  return m;
}

void PlaceBody(mjModel* m, int body, const Eigen::Isometry3d& X) {
  const Eigen::Vector3d p = X.translation() / kMm;
  const Eigen::Quaterniond q(X.linear());
  for (int i = 0; i < 3; ++i) m->body_pos[3 * body + i] = p[i];
  m->body_quat[4 * body + 0] = q.w();
  m->body_quat[4 * body + 1] = q.x();
  m->body_quat[4 * body + 2] = q.y();
  m->body_quat[4 * body + 3] = q.z();
}

// Reads the arm from the model at the zero pose `d`: OPW parameters, offsets and sign corrections from the joint
// axes (whatever the convention), joint limits and speeds. Returns the OPW model, or nothing (the reason in impl).
std::optional<planner::OpwArm> ReadArm(CellModel::Impl* impl, const mjData* d, const Eigen::Isometry3d& X_RW) {
  const mjModel* m = impl->m;
  const int fl = impl->flange;
  planner::ArmAxes axes;
  for (int j = 0; j < 6; ++j) {
    const int id = impl->jnt[j];
    axes.point_R[j] = X_RW * (Eigen::Vector3d(d->xanchor[3 * id], d->xanchor[3 * id + 1], d->xanchor[3 * id + 2]) * kMm);
    axes.axis_R[j] = X_RW.linear() * Eigen::Vector3d(d->xaxis[3 * id], d->xaxis[3 * id + 1], d->xaxis[3 * id + 2]);
  }
  axes.X_RF0 = X_RW * Pose(d->xpos + 3 * fl, d->xmat + 9 * fl);
  const std::optional<planner::OpwArm> opw = planner::OpwFromAxes(axes, &impl->not_opw_reason);
  planner::OpwArm& arm = impl->kinematics.arm;
  if (opw) arm = *opw;
  arm.name = "arm of " + impl->file.filename().string();
  const mjtNum* speed = m->numeric_data + m->numeric_adr[impl->speeds];
  for (int j = 0; j < 6; ++j) {
    arm.lower[j] = m->jnt_range[2 * impl->jnt[j]];
    arm.upper[j] = m->jnt_range[2 * impl->jnt[j] + 1];
    arm.max_speed[j] = speed[j] * kPi / 180.0;
  }
  arm.max_accel = arm.max_speed / planner::kAxisRampTimeS;  // no model gives accelerations (opw_arm.h)
  return opw;
}

// Reads the tool from the model at the zero pose `d`: the tcp site in the flange frame and the nozzle capsule in
// the TCP frame (rigid on the flange, so any pose gives it).
void ReadTool(CellModel::Impl* impl, const mjData* d) {
  const mjModel* m = impl->m;
  const int fl = impl->flange;
  const int ts = impl->tcp;
  impl->kinematics.X_FT =
      Pose(d->xpos + 3 * fl, d->xmat + 9 * fl).inverse() * Pose(d->site_xpos + 3 * ts, d->site_xmat + 9 * ts);
  const int g = impl->nozzle;
  const Eigen::Isometry3d X_TG =
      Pose(d->site_xpos + 3 * ts, d->site_xmat + 9 * ts).inverse() * Pose(d->geom_xpos + 3 * g, d->geom_xmat + 9 * g);
  const double half = m->geom_size[3 * g + 1] * kMm;
  impl->nozzle_a_T = X_TG * Eigen::Vector3d(0.0, 0.0, -half);
  impl->nozzle_b_T = X_TG * Eigen::Vector3d(0.0, 0.0, half);
  impl->nozzle_radius_mm = m->geom_size[3 * g] * kMm;
}

// The tilt-rotate positioner's offsets and tilt limits; throws InputError unless its bodies are unrotated with the
// tilt about x and the rotation about z. Returns X_WC, the table frame in world.
Eigen::Isometry3d ReadTiltRotate(CellModel::Impl* impl, const mjData* d) {
  const mjModel* m = impl->m;
  planner::CellKinematics& cell = impl->kinematics;
  const int tilt_body = m->jnt_bodyid[impl->jnt[6]];
  const int rot_body = m->jnt_bodyid[impl->jnt[7]];
  const Eigen::Isometry3d X_WA = Pose(d->xpos + 3 * tilt_body, d->xmat + 9 * tilt_body);
  const Eigen::Isometry3d X_WC = Pose(d->xpos + 3 * rot_body, d->xmat + 9 * rot_body);
  const Eigen::Isometry3d X_BA = cell.X_WB.inverse() * X_WA;
  const Eigen::Isometry3d X_AC = X_WA.inverse() * X_WC;
  const Eigen::Vector3d tilt_axis(m->jnt_axis + 3 * impl->jnt[6]);
  const Eigen::Vector3d rot_axis(m->jnt_axis + 3 * impl->jnt[7]);
  WAAM_THROW_UNLESS(X_BA.linear().isIdentity(1e-9) && X_AC.linear().isIdentity(1e-9) &&
                        (tilt_axis - Eigen::Vector3d::UnitX()).norm() < 1e-9 &&
                        (rot_axis - Eigen::Vector3d::UnitZ()).norm() < 1e-9 &&
                        tilt_body == m->body_parentid[rot_body] && m->body_parentid[tilt_body] == impl->positioner_base,
                    impl->file.string() << ": the positioner must be positioner_base -> body with pos_tilt (axis 1 0 0) "
                                           "-> body with pos_rot (axis 0 0 1), without rotated body frames");
  cell.positioner.p_BA = X_BA.translation();
  cell.positioner.p_AC = X_AC.translation();
  cell.positioner.tilt_lower = m->jnt_range[2 * impl->jnt[6]];
  cell.positioner.tilt_upper = m->jnt_range[2 * impl->jnt[6] + 1];
  return X_WC;
}

// The turntable's offset (in p_BA); throws InputError unless its body is unrotated and turns about z. Returns X_WC.
Eigen::Isometry3d ReadTurntable(CellModel::Impl* impl, const mjData* d) {
  const mjModel* m = impl->m;
  planner::CellKinematics& cell = impl->kinematics;
  const int rot_body = m->jnt_bodyid[impl->jnt[7]];
  const Eigen::Isometry3d X_WC = Pose(d->xpos + 3 * rot_body, d->xmat + 9 * rot_body);
  const Eigen::Isometry3d X_BC = cell.X_WB.inverse() * X_WC;
  const Eigen::Vector3d rot_axis(m->jnt_axis + 3 * impl->jnt[7]);
  WAAM_THROW_UNLESS(X_BC.linear().isIdentity(1e-9) && (rot_axis - Eigen::Vector3d::UnitZ()).norm() < 1e-9 &&
                        m->body_parentid[rot_body] == impl->positioner_base,
                    impl->file.string() << ": the turntable must be positioner_base -> body with pos_rot (axis 0 0 1), "
                                           "without a rotated body frame");
  cell.positioner.p_BA = X_BC.translation();
  return X_WC;
}

// Reads the positioner chain from the model at the zero pose `d`: B -> tilt axis frame A -> table frame C -> plate
// top (part_origin). A turntable has no A (the table frame C sits on B, p_BA holds its offset), no positioner no C
// either (the plate is fixed: C = B).
void ReadPositioner(CellModel::Impl* impl, const mjData* d) {
  const mjModel* m = impl->m;
  planner::CellKinematics& cell = impl->kinematics;
  const int pb = impl->positioner_base;
  cell.X_WB = Pose(d->xpos + 3 * pb, d->xmat + 9 * pb);
  cell.positioner.type = impl->positioner_type;
  Eigen::Isometry3d X_WC = cell.X_WB;
  cell.positioner.p_BA = Eigen::Vector3d::Zero();
  cell.positioner.p_AC = Eigen::Vector3d::Zero();
  cell.positioner.tilt_lower = cell.positioner.tilt_upper = 0.0;
  cell.positioner.rotation_lower = cell.positioner.rotation_upper = 0.0;
  if (impl->positioner_type == planner::PositionerType::kTiltRotate) X_WC = ReadTiltRotate(impl, d);
  if (impl->positioner_type == planner::PositionerType::kTurntable) X_WC = ReadTurntable(impl, d);
  if (impl->positioner_type != planner::PositionerType::kNone) {
    cell.positioner.rotation_lower = m->jnt_range[2 * impl->jnt[7]];
    cell.positioner.rotation_upper = m->jnt_range[2 * impl->jnt[7] + 1];
  }
  const int po = impl->part_origin;
  cell.positioner.X_CP = X_WC.inverse() * Pose(d->site_xpos + 3 * po, d->site_xmat + 9 * po);
  const mjtNum* speed = m->numeric_data + m->numeric_adr[impl->speeds];
  cell.positioner.tilt_max_speed = speed[6] * kPi / 180.0;
  cell.positioner.rotation_max_speed = speed[7] * kPi / 180.0;
  cell.positioner.tilt_max_accel = cell.positioner.tilt_max_speed / planner::kAxisRampTimeS;
  cell.positioner.rotation_max_accel = cell.positioner.rotation_max_speed / planner::kAxisRampTimeS;
}

// The largest flange error (mm, plus 1000 x the rotation matrices' difference) of the closed form against
// MuJoCo's forward kinematics on 50 seeded random joint vectors within the limits; `d` is moved.
double ClosedFormError(const CellModel::Impl& impl, mjData* d, const Eigen::Isometry3d& X_RW) {
  const planner::OpwArm& arm = impl.kinematics.arm;
  const int fl = impl.flange;
  std::mt19937_64 rng(2024);
  double worst = 0.0;
  for (int trial = 0; trial < 50; ++trial) {
    planner::Joints6 q;
    for (int j = 0; j < 6; ++j) q[j] = std::uniform_real_distribution<double>(arm.lower[j], arm.upper[j])(rng);
    for (int j = 0; j < 6; ++j) d->qpos[impl.qadr[j]] = q[j];
    mj_kinematics(impl.m, d);
    const Eigen::Isometry3d X_RF = X_RW * Pose(d->xpos + 3 * fl, d->xmat + 9 * fl);
    const Eigen::Isometry3d X_fk = planner::ForwardKinematics(arm, q);
    worst = std::max(worst, (X_RF.translation() - X_fk.translation()).norm() +
                                1000.0 * (X_RF.linear() - X_fk.linear()).norm());
  }
  return worst;
}

// Reads the kinematics, the closed-form test and the nozzle from the model at the zero pose.
void ReadKinematics(CellModel::Impl* impl) {
  ScratchData scratch(impl->m);
  mjData* d = scratch.get();
  mj_kinematics(impl->m, d);
  const int rb = impl->robot_base;
  impl->kinematics.X_WR = Pose(d->xpos + 3 * rb, d->xmat + 9 * rb);
  const Eigen::Isometry3d X_RW = impl->kinematics.X_WR.inverse();
  const std::optional<planner::OpwArm> opw = ReadArm(impl, d, X_RW);
  ReadTool(impl, d);
  ReadPositioner(impl, d);
  // The closed form must reproduce MuJoCo's forward kinematics of the flange (to 1e-6 mm) on random joints.
  impl->closed_form = opw.has_value() && ClosedFormError(*impl, d, X_RW) < 1e-6;
  if (opw && !impl->closed_form) impl->not_opw_reason = "the OPW model differs from MuJoCo's forward kinematics";
}

// Damped least-squares IK on the model with its own data (see CellModel::SolveNumericIk).
bool SolveIkOnModel(const CellModel::Impl& impl, const Eigen::Isometry3d& X_RF, const planner::Joints6& seed,
                    planner::Joints6* q_out, double* residual_mm) {
  const mjModel* m = impl.m;
  ScratchData scratch(m);
  mjData* d = scratch.get();  // every axis at 0 but the arm's: the flange pose in R does not depend on the others
  const int rb = impl.robot_base;
  const int fl = impl.flange;
  planner::Joints6 q;
  for (int j = 0; j < 6; ++j) {
    const int id = impl.jnt[j];
    q[j] = std::clamp(seed[j], m->jnt_range[2 * id], m->jnt_range[2 * id + 1]);
  }
  constexpr double kLever = 1000.0;  // rotation errors count at 1 m, like the IK tests
  std::vector<mjtNum> jacp(3 * m->nv), jacr(3 * m->nv);
  double residual = 0.0;
  for (int iteration = 0; iteration < 200; ++iteration) {
    for (int j = 0; j < 6; ++j) d->qpos[impl.qadr[j]] = q[j];
    mj_kinematics(m, d);
    mj_comPos(m, d);
    const Eigen::Isometry3d X_WR = Pose(d->xpos + 3 * rb, d->xmat + 9 * rb);
    const Eigen::Isometry3d X_WF = Pose(d->xpos + 3 * fl, d->xmat + 9 * fl);
    const Eigen::Isometry3d X_WF_goal = X_WR * X_RF;
    Eigen::Matrix<double, 6, 1> e;
    e.head<3>() = X_WF_goal.translation() - X_WF.translation();
    const Eigen::AngleAxisd rot(X_WF_goal.linear() * X_WF.linear().transpose());
    e.tail<3>() = rot.angle() * rot.axis() * kLever;
    residual = e.head<3>().norm() + e.tail<3>().norm();
    if (residual < 1e-6) {
      *q_out = q;
      *residual_mm = residual;
      return true;
    }
    mj_jacBody(m, d, jacp.data(), jacr.data(), fl);
    Eigen::Matrix<double, 6, 6> J;
    for (int j = 0; j < 6; ++j) {
      const int dof = m->jnt_dofadr[impl.jnt[j]];
      for (int r = 0; r < 3; ++r) {
        J(r, j) = jacp[r * m->nv + dof] * kMm;
        J(3 + r, j) = jacr[r * m->nv + dof] * kLever;
      }
    }
    // Damped least squares (Levenberg-Marquardt step), at most 0.2 rad per joint and iteration.
    const Eigen::Matrix<double, 6, 6> A = J * J.transpose() + 1e-4 * Eigen::Matrix<double, 6, 6>::Identity();
    planner::Joints6 dq = J.transpose() * A.ldlt().solve(e);
    const double largest = dq.cwiseAbs().maxCoeff();
    if (largest > 0.2) dq *= 0.2 / largest;
    for (int j = 0; j < 6; ++j) {
      const int id = impl.jnt[j];
      q[j] = std::clamp(q[j] + dq[j], m->jnt_range[2 * id], m->jnt_range[2 * id + 1]);
    }
  }
  *q_out = q;
  *residual_mm = residual;
  return false;
}

std::shared_ptr<const CellModel::Impl> BuildModel(const MjcfSource& mjcf, const Eigen::Isometry3d* X_WR,
                                                  const Eigen::Isometry3d* X_WB,
                                                  const CellModel::RobotInfo* info = nullptr) {
  auto impl = std::make_shared<CellModel::Impl>();
  mjModel* editable = LoadModel(mjcf, impl.get());
  if (X_WR) PlaceBody(editable, impl->robot_base, *X_WR);
  if (X_WB) PlaceBody(editable, impl->positioner_base, *X_WB);
  ReadKinematics(impl.get());
  if (info) {
    impl->robot = *info;
  } else if (mjcf.builtin) {
    impl->robot.name = "FANUC ARC Mate 100iC/12";
    impl->robot.source = "builtin";
  } else {
    impl->robot.name = impl->kinematics.arm.name;
    impl->robot.source = mjcf.file.string();
  }
  impl->kinematics.arm.name = impl->robot.name;
  return impl;
}

}  // namespace

CellModel::CellModel(const MjcfSource& mjcf, const Eigen::Isometry3d& X_WR, const Eigen::Isometry3d& X_WB)
    : impl_(BuildModel(mjcf, &X_WR, &X_WB)) {}

CellModel::CellModel(const MjcfSource& mjcf) : impl_(BuildModel(mjcf, nullptr, nullptr)) {}

CellModel CellModel::FromXml(const MjcfSource& mjcf, const RobotInfo& info, const Eigen::Isometry3d& X_WR,
                             const Eigen::Isometry3d& X_WB) {
  if (!mjcf.file.empty()) return CellModel(FromImplTag{}, BuildModel(mjcf, &X_WR, &X_WB, &info));
  MjcfSource named = mjcf;
  named.file = info.source;
  return CellModel(FromImplTag{}, BuildModel(named, &X_WR, &X_WB, &info));
}

const CellModel::RobotInfo& CellModel::robot() const { return impl_->robot; }

planner::CellKinematics CellModel::kinematics() const {
  planner::CellKinematics kin = impl_->kinematics;
  if (!impl_->closed_form) {
    // Not an OPW arm: the numerical IK on this model takes over, holding the model.
    kin.numeric_ik = [model = impl_](const Eigen::Isometry3d& X_RF, const planner::Joints6& seed, planner::Joints6* q,
                                     double* residual) { return SolveIkOnModel(*model, X_RF, seed, q, residual); };
  }
  return kin;
}
bool CellModel::closed_form() const { return impl_->closed_form; }
const std::string& CellModel::not_closed_form_reason() const { return impl_->not_opw_reason; }
const fs::path& CellModel::file() const { return impl_->file; }

bool CellModel::SolveNumericIk(const Eigen::Isometry3d& X_RF, const planner::Joints6& seed, planner::Joints6* q,
                               double* residual_mm) const {
  return SolveIkOnModel(*impl_, X_RF, seed, q, residual_mm);
}

void CellModel::NozzleInTcp(Eigen::Vector3d* a_T, Eigen::Vector3d* b_T, double* radius_mm) const {
  *a_T = impl_->nozzle_a_T;
  *b_T = impl_->nozzle_b_T;
  *radius_mm = impl_->nozzle_radius_mm;
}

CellState::CellState(const CellModel& model)
    : model_(model.impl_), data_(std::make_unique<Data>(model.impl_->m)) {
  mj_kinematics(model_->m, data_->d.get());
}

CellState::~CellState() = default;

void CellState::SetJoints(const Joints8& q) {
  mjData* d = data_->d.get();
  for (int j = 0; j < 8; ++j) {
    if (model_->qadr[j] >= 0) d->qpos[model_->qadr[j]] = q[j];  // an axis the cell lacks stays at 0
  }
  mj_kinematics(model_->m, d);
}

Eigen::Isometry3d CellState::TcpPose() const {
  const mjData* d = data_->d.get();
  const int s = model_->tcp;
  return Pose(d->site_xpos + 3 * s, d->site_xmat + 9 * s);
}

int CellState::Collide(double tolerance_mm, std::vector<CellContact>* out, double* clearance_mm) {
  const mjModel* m = model_->m;
  mjData* d = data_->d.get();
  mj_collision(m, d);
  data_->collide_xpos.assign(d->geom_xpos, d->geom_xpos + 3 * m->ngeom);
  data_->collide_xmat.assign(d->geom_xmat, d->geom_xmat + 9 * m->ngeom);
  int n = 0;
  double clearance = CellModel::kClearanceMarginMm;
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    clearance = std::min(clearance, c.dist * kMm);
    const double penetration = -c.dist * kMm;
    if (penetration <= tolerance_mm) continue;
    CellContact contact;
    contact.body1 = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[c.geom1]);
    contact.body2 = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[c.geom2]);
    contact.penetration_mm = penetration;
    contact.p_W = Eigen::Vector3d(c.pos[0], c.pos[1], c.pos[2]) * kMm;
    out->push_back(std::move(contact));
    ++n;
  }
  if (clearance_mm) *clearance_mm = clearance;
  return n;
}

double CellState::MotionSinceCollide() const {
  const mjModel* m = model_->m;
  const mjData* d = data_->d.get();
  if (data_->collide_xpos.size() != static_cast<std::size_t>(3 * m->ngeom)) return 1e300;
  double largest = 0.0;
  for (int g = 0; g < m->ngeom; ++g) {
    const mjtNum* p0 = data_->collide_xpos.data() + 3 * g;
    const mjtNum* p1 = d->geom_xpos + 3 * g;
    const double move = std::sqrt((p1[0] - p0[0]) * (p1[0] - p0[0]) + (p1[1] - p0[1]) * (p1[1] - p0[1]) +
                                   (p1[2] - p0[2]) * (p1[2] - p0[2]));
    // Rotation angle between the two orientations: trace(R0^T R1) = 1 + 2 cos(angle).
    const mjtNum* r0 = data_->collide_xmat.data() + 9 * g;
    const mjtNum* r1 = d->geom_xmat + 9 * g;
    double trace = 0.0;
    for (int k = 0; k < 9; ++k) trace += r0[k] * r1[k];
    const double angle = std::acos(std::clamp(0.5 * (trace - 1.0), -1.0, 1.0));
    const double bound = m->geom_type[g] == mjGEOM_PLANE ? move : move + angle * m->geom_rbound[g];
    largest = std::max(largest, bound * kMm);
  }
  return largest;
}

std::vector<CellShape> CellState::Shapes() const {
  const mjModel* m = model_->m;
  const mjData* d = data_->d.get();
  std::vector<CellShape> shapes;
  for (int g = 0; g < m->ngeom; ++g) {
    CellShape s;
    switch (m->geom_type[g]) {
      case mjGEOM_PLANE: s.type = CellShape::Type::kPlane; break;
      case mjGEOM_SPHERE: s.type = CellShape::Type::kSphere; break;
      case mjGEOM_CAPSULE: s.type = CellShape::Type::kCapsule; break;
      case mjGEOM_CYLINDER: s.type = CellShape::Type::kCylinder; break;
      case mjGEOM_BOX: s.type = CellShape::Type::kBox; break;
      default: s.type = CellShape::Type::kOther; break;
    }
    s.body = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[g]) ? mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[g]) : "world";
    s.size_mm = Eigen::Vector3d(m->geom_size[3 * g], m->geom_size[3 * g + 1], m->geom_size[3 * g + 2]) * kMm;
    s.X_WG = Pose(d->geom_xpos + 3 * g, d->geom_xmat + 9 * g);
    s.rgba = Eigen::Vector4f(m->geom_rgba[4 * g], m->geom_rgba[4 * g + 1], m->geom_rgba[4 * g + 2],
                             m->geom_rgba[4 * g + 3]);
    shapes.push_back(s);
  }
  return shapes;
}

namespace {

// A geom's type as a CellShape type.
CellShape::Type ShapeType(int mj_type) {
  switch (mj_type) {
    case mjGEOM_PLANE: return CellShape::Type::kPlane;
    case mjGEOM_SPHERE: return CellShape::Type::kSphere;
    case mjGEOM_CAPSULE: return CellShape::Type::kCapsule;
    case mjGEOM_CYLINDER: return CellShape::Type::kCylinder;
    case mjGEOM_BOX: return CellShape::Type::kBox;
    case mjGEOM_MESH: return CellShape::Type::kMesh;
    default: return CellShape::Type::kOther;
  }
}

}  // namespace

std::vector<CellBody> CellModel::Bodies() const {
  const mjModel* m = impl_->m;
  std::vector<CellBody> bodies;
  for (int b = 0; b < m->nbody; ++b) {
    if (m->body_geomnum[b] == 0) continue;
    CellBody body;
    const char* name = mj_id2name(m, mjOBJ_BODY, b);
    body.name = name ? name : "world";
    if (m->body_jntnum[b] > 0) {
      const char* joint = mj_id2name(m, mjOBJ_JOINT, m->body_jntadr[b]);
      body.joint = joint ? joint : "";
    }
    for (int g = m->body_geomadr[b]; g < m->body_geomadr[b] + m->body_geomnum[b]; ++g) {
      CellShape s;
      s.type = ShapeType(m->geom_type[g]);
      s.body = body.name;
      s.size_mm = Eigen::Vector3d(m->geom_size[3 * g], m->geom_size[3 * g + 1], m->geom_size[3 * g + 2]) * kMm;
      const mjtNum* q = m->geom_quat + 4 * g;
      s.X_WG = Eigen::Isometry3d::Identity();
      s.X_WG.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
      s.X_WG.translation() = Eigen::Vector3d(m->geom_pos[3 * g], m->geom_pos[3 * g + 1], m->geom_pos[3 * g + 2]) * kMm;
      s.rgba = Eigen::Vector4f(m->geom_rgba[4 * g], m->geom_rgba[4 * g + 1], m->geom_rgba[4 * g + 2],
                               m->geom_rgba[4 * g + 3]);
      std::vector<Eigen::Vector3f> vertices;
      std::vector<Eigen::Vector3i> triangles;
      const int mesh = m->geom_dataid[g];
      if (m->geom_type[g] == mjGEOM_MESH && mesh >= 0) {
        // MuJoCo keeps mesh vertices in the geom frame (it moved the geom to the mesh's inertial frame on load).
        const float* v = m->mesh_vert + 3 * m->mesh_vertadr[mesh];
        for (int i = 0; i < m->mesh_vertnum[mesh]; ++i) {
          vertices.emplace_back(v[3 * i] * kMm, v[3 * i + 1] * kMm, v[3 * i + 2] * kMm);
        }
        const int* f = m->mesh_face + 3 * m->mesh_faceadr[mesh];
        for (int i = 0; i < m->mesh_facenum[mesh]; ++i) triangles.emplace_back(f[3 * i], f[3 * i + 1], f[3 * i + 2]);
      }
      body.geoms.push_back(s);
      body.mesh_vertices_mm.push_back(std::move(vertices));
      body.mesh_triangles.push_back(std::move(triangles));
    }
    bodies.push_back(std::move(body));
  }
  return bodies;
}

std::vector<Eigen::Isometry3d> CellState::BodyPoses() const {
  const mjModel* m = model_->m;
  const mjData* d = data_->d.get();
  std::vector<Eigen::Isometry3d> poses;
  for (int b = 0; b < m->nbody; ++b) {
    if (m->body_geomnum[b] > 0) poses.push_back(Pose(d->xpos + 3 * b, d->xmat + 9 * b));
  }
  return poses;
}

}  // namespace waam::twin
