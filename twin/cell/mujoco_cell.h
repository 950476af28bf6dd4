// The MuJoCo model of the welding cell behind a MuJoCo-free interface: a const CellModel (load and place once, read
// the kinematics) and a per-thread CellState (set the eight axes, forward kinematics, collision detection, shapes).
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "planner/kinematics/cell_motion.h"
#include "twin/cell/convex_distance.h"

namespace waam::twin {

// One penetrating contact between two bodies of the cell.
struct CellContact {
  std::string body1;
  std::string body2;
  double penetration_mm = 0.0;                        // > 0
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();      // contact point in the world, mm
};

// A collision shape in the world, for pictures.
struct CellShape {
  enum class Type { kPlane, kSphere, kCapsule, kCylinder, kBox, kOther, kMesh };  // kMesh: CellModel::Bodies() only
  Type type = Type::kOther;
  std::string body;
  Eigen::Vector3d size_mm = Eigen::Vector3d::Zero();     // MuJoCo geom_size in mm (radius, half-length, ...)
  Eigen::Isometry3d X_WG = Eigen::Isometry3d::Identity();  // geom frame in the world, mm
  Eigen::Vector4f rgba = Eigen::Vector4f::Ones();
};

// A body of the cell with its collision geoms in the body frame, for viewers (the geometry once, then the body
// poses per frame from CellState::BodyPoses()).
struct CellBody {
  std::string name;
  std::string joint;              // the joint that moves it relative to its parent ("" when welded to it)
  std::vector<CellShape> geoms;   // each X_WG holds X_BG here: the geom in the body frame, mm
  // For each geom (same index): a mesh geom's vertices in the geom frame (mm) and its triangles; empty otherwise.
  std::vector<std::vector<Eigen::Vector3f>> mesh_vertices_mm;
  std::vector<std::vector<Eigen::Vector3i>> mesh_triangles;
};

// The cell's collision geometry for distance queries (twin/cell/cell_sweep.h): MuJoCo's geoms as convex shapes (a
// mesh as its convex hull, as MuJoCo collides it), the pairs its collision detection tests, and how far from each
// of the eight axes any point of each shape can lie.
struct CellCollisionGeometry {
  std::vector<ConvexShape> shapes;  // one per geom that may collide (contype or conaffinity set)
  std::vector<int> geom;            // the model's geom index of each shape
  std::vector<std::string> body;    // the name of each shape's body ("world" for the world body)
  // Per shape, per axis (j1..j6, pos_tilt, pos_rot): when the axis moves the shape, a bound on the distance from the
  // axis's anchor to any point of the shape in every configuration (the lengths along the chain of bodies between
  // them plus the shape's bounding radius), mm; 0 when it does not move it.
  std::vector<Eigen::Matrix<double, 8, 1>> lever_mm;
  std::vector<std::array<int, 2>> pairs;  // indices into `shapes`: the pairs MuJoCo's collision detection tests
  // Why distances cannot be bounded on this model, one line, empty when they can: a height field, an empty mesh or
  // one that is not closed (names the geom and its body), or the model's RobotInfo::incomplete_geometry.
  std::string unsupported;
  // The model's bodies as a tree for ShapePosesAt (MuJoCo's body order: a parent before its children; 0 the world).
  struct Link {
    int parent = 0;                                          // the parent's index (the world's own: 0)
    Eigen::Isometry3d X_PL = Eigen::Isometry3d::Identity();  // the body in its parent's frame at zero axes, mm
    int axis = -1;                      // which of the eight axes turns it about its hinge (-1: none)
    Eigen::Vector3d anchor_L = Eigen::Vector3d::Zero();      // the hinge's anchor in the body frame, mm
    Eigen::Vector3d axis_L = Eigen::Vector3d::UnitZ();       // the hinge's unit axis in the body frame
    double q0 = 0.0;                                         // the hinge's reference angle, rad
  };
  std::vector<Link> links;
  std::vector<int> link;                   // per shape: its body's index into links
  std::vector<Eigen::Isometry3d> X_LG;     // per shape: the geom in its body's frame, mm
  // The torch's gas nozzle (the capsule geom `nozzle`, along z of its frame N): its body's link, its pose in that
  // body (mm), and the lever bound of each axis over it (as lever_mm), for the nozzle against the deposited part.
  int nozzle_link = 0;
  Eigen::Isometry3d X_LN = Eigen::Isometry3d::Identity();
  Eigen::Matrix<double, 8, 1> nozzle_lever_mm = Eigen::Matrix<double, 8, 1>::Zero();
};

// The world pose (mm) of each body of `geometry.links` at the eight axes `q` (rad), into `X_WL` (resized), as
// MuJoCo's forward kinematics places them.
void LinkPosesAt(const CellCollisionGeometry& geometry, const planner::Joints8& q, std::vector<Eigen::Isometry3d>* X_WL);

// The world pose (mm) of each shape of `geometry` at the eight axes `q` (rad), into `X_WG` (resized), from the
// geometry's own tree: the poses MuJoCo's forward kinematics gives (CellState::ShapePoses after SetJoints, to
// rounding), without an mjData and at a fraction of its cost (only the bodies, not the model's sites and visual geoms).
void ShapePosesAt(const CellCollisionGeometry& geometry, const planner::Joints8& q, std::vector<Eigen::Isometry3d>* X_WG);

// A cell model's MJCF as data (read by analysis/cell_files.h; the twin opens no file): the text, the file that names
// it, and the bytes of every file the text names (meshes, textures, included MJCF). MuJoCo finds each asset by its
// file name without the folders, in any case, so no two assets may share that name.
struct MjcfSource {
  std::string xml;                                          // the MJCF text
  std::filesystem::path file;                               // names the model in messages and CellModel::file()
  std::vector<std::pair<std::string, std::string>> assets;  // (file name as the text gives it, its bytes)
  bool builtin = false;                                     // the built-in cell (twin/data/cell_arcmate100ic.xml)
};

// The cell model, after MuJoCo's model/data split: the MJCF loaded and placed once, then immutable. It owns the
// mjModel and what is read from it (the kinematics, the nozzle); it is shared by reference (copies share the same
// model) and may be used from several threads at once. What changes with the joints lives in a CellState.
class CellModel {
 public:
  // Compiles the MJCF `mjcf` with the arm base frame R at X_WR and the positioner base frame B at X_WB in the world
  // (mm), and reads its kinematics: the arm's OPW parameters, limits and speeds,
  // the tool (tcp site in the flange frame), the positioner chain and the plate top (part_origin site) as X_CP. The
  // OPW parameters, offsets and sign corrections are read off the joint axes at the zero pose (any vendor
  // convention); an arm whose axes are not of the OPW kind, or whose closed form differs from MuJoCo's forward
  // kinematics on random poses, gets the numerical IK on this model. Throws InputError naming the file and MuJoCo's message for a
  // file that does not parse or compile, that lacks a required joint, body, site or field, or whose positioner chain
  // is not tilt-about-x then rotate-about-z. The positioner's type is read off its joints: pos_tilt and pos_rot
  // (tilt_rotate), pos_rot alone (turntable: positioner_base -> table about z) or neither (none: a fixed plate).
  CellModel(const MjcfSource& mjcf, const Eigen::Isometry3d& X_WR, const Eigen::Isometry3d& X_WB);
  // The same with the bases where the file puts them.
  explicit CellModel(const MjcfSource& mjcf);

  // What the arm is, for reports: name (vendor first), source (builtin, a preset name or the model's path) and the
  // model's names of j1..j6.
  struct RobotInfo {
    std::string name;
    std::string source;
    std::array<std::string, 6> joints = {"j1", "j2", "j3", "j4", "j5", "j6"};
    // Why the model's geoms do not describe every body (e.g. a URDF link drawn but without collision geometry): one
    // line, which CollisionGeometry() reports as `unsupported` (the continuous check then runs discrete); empty: none.
    std::string incomplete_geometry = {};
  };
  // A cell model (a composed cell, e.g. around a URDF arm, or a preset's) placed like the constructor above and
  // reported as `info`; `mjcf.file` (default: info.source) is the model's file() and names it in messages.
  static CellModel FromXml(const MjcfSource& mjcf, const RobotInfo& info, const Eigen::Isometry3d& X_WR,
                           const Eigen::Isometry3d& X_WB);
  const RobotInfo& robot() const;

  // The cell's kinematics (a copy; the numerical IK it may carry holds this model, safe to call from any thread).
  planner::CellKinematics kinematics() const;
  // True when the arm has the closed-form (OPW) kinematics.
  bool closed_form() const;
  // Why the closed form does not apply (empty when it does).
  const std::string& not_closed_form_reason() const;

  // Damped least-squares IK of the flange pose X_RF (arm base frame, mm) on the model, from `seed` (rad), joints
  // kept inside their limits. Returns false with the remaining error (mm, rotation counted at 1 m) if it does not
  // converge to 1e-6 mm within 200 iterations. Safe to call from several threads: each call has its own mjData.
  bool SolveNumericIk(const Eigen::Isometry3d& X_RF, const planner::Joints6& seed, planner::Joints6* q,
                      double* residual_mm) const;

  // The gas nozzle capsule in the TCP frame: end points (mm) and radius (mm).
  void NozzleInTcp(Eigen::Vector3d* a_T, Eigen::Vector3d* b_T, double* radius_mm) const;
  const std::filesystem::path& file() const;
  // Every body that has collision geoms (the world body with the floor included), in the model's order.
  std::vector<CellBody> Bodies() const;
  // The collision geometry for distance queries (twin/cell/mujoco_geometry.cc).
  CellCollisionGeometry CollisionGeometry() const;

  // Every geom is reported in contact up to this distance apart, which gives CellState::Collide its clearance.
  static constexpr double kClearanceMarginMm = 10.0;

  struct Impl;  // the MuJoCo side, in mujoco_cell.cc

 private:
  struct FromImplTag {};
  CellModel(FromImplTag, std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  std::shared_ptr<const Impl> impl_;
  friend class CellState;
};

// The state of one use of a CellModel (one mjData): the eight axes set last, forward kinematics and collisions at
// them. One per thread; the model must outlive it.
class CellState {
 public:
  explicit CellState(const CellModel& model);
  ~CellState();
  CellState(const CellState&) = delete;
  CellState& operator=(const CellState&) = delete;

  // Sets the eight axes (rad) and runs forward kinematics.
  void SetJoints(const planner::Joints8& q);
  // TCP pose in the world after SetJoints, mm.
  Eigen::Isometry3d TcpPose() const;
  // Runs collision detection for the joints set last; appends contacts deeper than `tolerance_mm` to `out` and
  // returns their number. Every geom carries a margin of CellModel::kClearanceMarginMm, so `*clearance_mm` (may be
  // null) is the smallest distance between any two bodies that may collide, capped at that margin (negative when
  // penetrating).
  int Collide(double tolerance_mm, std::vector<CellContact>* out, double* clearance_mm);
  // Upper bound (mm) on how far any point of any geom has moved since the last Collide(): per geom, the move of
  // its centre plus its rotation angle times its bounding radius. While twice this stays below the clearance of
  // the last Collide(), no new contact can have appeared.
  double MotionSinceCollide() const;
  // The world pose (mm) of each shape of `geometry` (made by this model's CollisionGeometry()) at the joints set
  // last, into `X_WG` (resized to the shapes' number).
  void ShapePoses(const CellCollisionGeometry& geometry, std::vector<Eigen::Isometry3d>* X_WG) const;
  // All collision shapes at the joints set last.
  std::vector<CellShape> Shapes() const;
  // Pose in the world (mm) of each body of CellModel::Bodies(), same order, at the joints set last.
  std::vector<Eigen::Isometry3d> BodyPoses() const;

 private:
  struct Data;
  std::shared_ptr<const CellModel::Impl> model_;
  std::unique_ptr<Data> data_;
};

}  // namespace waam::twin
