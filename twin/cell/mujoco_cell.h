// The MuJoCo model of the welding cell behind a MuJoCo-free interface: load, place, set the eight axes, run forward
// kinematics and collision detection, and read the geometry the planner's kinematics needs.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "planner/kinematics/cell_motion.h"

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
  enum class Type { kPlane, kSphere, kCapsule, kCylinder, kBox, kOther };
  Type type = Type::kOther;
  std::string body;
  Eigen::Vector3d size_mm = Eigen::Vector3d::Zero();     // MuJoCo geom_size in mm (radius, half-length, ...)
  Eigen::Isometry3d X_WG = Eigen::Isometry3d::Identity();  // geom frame in the world, mm
  Eigen::Vector4f rgba = Eigen::Vector4f::Ones();
};

// Owns the mjModel (const after placement) and one mjData.
class MujocoCell {
 public:
  // The built-in model, twin/data/cell_arcmate100ic.xml.
  static std::filesystem::path BuiltinModelPath();

  // Loads an MJCF file (the built-in one when `mjcf` is empty). Throws InputError naming the file and MuJoCo's
  // message for a file that does not parse or compile, or that lacks a required joint, body, site or field.
  explicit MujocoCell(const std::filesystem::path& mjcf);
  ~MujocoCell();
  MujocoCell(const MujocoCell&) = delete;
  MujocoCell& operator=(const MujocoCell&) = delete;

  // Moves the arm base and the positioner base to the given world poses (mm).
  void Place(const Eigen::Isometry3d& X_WR, const Eigen::Isometry3d& X_WB);

  // The cell's kinematics read from the model: the arm's OPW parameters, limits and speeds, the tool (tcp site in
  // the flange frame), the positioner chain and the plate top (part_origin site) as X_CP. If the arm is not of the
  // OPW kind in the FANUC joint convention (its MuJoCo forward kinematics differ from the closed form), the result
  // carries a numerical IK on this model instead (valid while this object lives). Throws InputError for a
  // positioner chain that is not tilt-about-x then rotate-about-z.
  planner::CellKinematics Kinematics() const;

  // True when the arm has the closed-form (OPW) kinematics; known after Kinematics().
  bool closed_form() const { return closed_form_; }

  // Damped least-squares IK of the flange pose X_RF (arm base frame, mm) on the model, from `seed` (rad), joints
  // kept inside their limits. Returns false with the remaining error (mm, rotation counted at 1 m) if it does not
  // converge to 1e-6 mm within 200 iterations.
  bool SolveNumericIk(const Eigen::Isometry3d& X_RF, const planner::Joints6& seed, planner::Joints6* q,
                      double* residual_mm) const;

  // Sets the eight axes (rad) and runs forward kinematics.
  void SetJoints(const planner::Joints8& q);
  // TCP pose in the world after SetJoints, mm.
  Eigen::Isometry3d TcpPose() const;
  // Runs collision detection for the joints set last; appends contacts deeper than `tolerance_mm` to `out` and
  // returns their number. Every geom carries a margin of kClearanceMarginMm, so `*clearance_mm` (may be null) is the
  // smallest distance between any two bodies that may collide, capped at that margin (negative when penetrating).
  int Collide(double tolerance_mm, std::vector<CellContact>* out, double* clearance_mm);

  // Upper bound (mm) on how far any point of any geom has moved since the last Collide(): per geom, the move of
  // its centre plus its rotation angle times its bounding radius. While twice this stays below the clearance of
  // the last Collide(), no new contact can have appeared.
  double MotionSinceCollide() const;

  static constexpr double kClearanceMarginMm = 10.0;

  // The gas nozzle capsule in the TCP frame: end points (mm) and radius (mm).
  void NozzleInTcp(Eigen::Vector3d* a_T, Eigen::Vector3d* b_T, double* radius_mm) const;
  // All collision shapes at the joints set last.
  std::vector<CellShape> Shapes() const;
  const std::filesystem::path& file() const { return file_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::filesystem::path file_;
  mutable bool closed_form_ = true;
};

}  // namespace waam::twin
