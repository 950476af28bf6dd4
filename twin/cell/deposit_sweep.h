// Continuous mode's torch against the part built so far: the nozzle swept over the joint-space line of every move,
// with a clearance lower bound from the deposit map, by conservative advancement within the move.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "planner/kinematics/cell_motion.h"
#include "twin/cell/deposit_map.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {

// The nozzle capsule in the part frame P: end points (mm); its radius is the sweep's.
struct NozzleInPart {
  Eigen::Vector3d a_P = Eigen::Vector3d::Zero(), b_P = Eigen::Vector3d::Zero();
};

// A contact of the nozzle with the deposited metal within a move.
struct DepositContact {
  double t_s = 0.0;            // time of first contact (the nozzle within contact_mm of the metal), s
  bool between_samples = false;  // strictly between the move's two samples
  double penetration_mm = 0.0;   // the deepest penetration at probes from there to the move's end, mm
};

// Sweeps the nozzle over each move against the deposit as it stands when the move's end sample is checked (the
// metal laid before the move's start; the bead the move lays lies under the torch). Per move from sample a to b:
// the distance bounds d_a, d_b at the ends (the nozzle's lowest point above the deposit's top, else the deposit
// map's column bound) and the bound M on how far nozzle and part approach over the move (each axis's travel times
// its lever: the arm's over the nozzle, the positioner's over the part's box) certify the move when
// (d_a + d_b - M) / 2 > contact_mm (or min(d_a, d_b) when |d_a - d_b| >= M); otherwise the move is advanced from a
// by d - contact_mm / 2 of travel at a time, the nozzle posed by forward kinematics between the samples, until it is
// certified or comes within contact_mm (a contact, then probed for its depth).
class DepositSweep {
 public:
  // `geometry`: cell.CollisionGeometry(); `kin`: the kinematics the motion was planned on (positioner and X_WB,
  // part frame included); `part_box_P`: a box in P holding all metal the motion lays (mm); contact, probe and
  // tolerance as SweepOptions (mm).
  DepositSweep(const CellModel& cell, const CellCollisionGeometry& geometry, const planner::CellKinematics& kin,
               const Eigen::AlignedBox3d& part_box_P, double contact_mm, double probe_mm, double tolerance_mm);

  // The move from sample a to b (consecutive, both reachable) with the nozzle's capsule at each (as the check's
  // per-sample test computes it) against `deposit`. A contact deeper than the tolerance, or none.
  std::optional<DepositContact> Move(const planner::CellSample& a, const NozzleInPart& n_a,
                                     const planner::CellSample& b, const NozzleInPart& n_b, const DepositMap& deposit);

  // Lower bound on the nozzle's distance from the deposited metal over every move swept (minus the deepest
  // penetration when there was a contact; +inf when nothing was swept), mm.
  double certified_clearance_mm() const { return deepest_ > 0.0 ? -deepest_ : certified_; }
  std::size_t queries() const { return queries_; }  // deposit-map distance bounds computed
  std::size_t poses() const { return poses_; }      // forward kinematics between samples

 private:
  NozzleInPart PoseAt(const planner::Joints8& q);
  double Bound(const NozzleInPart& n, const DepositMap& deposit, double cap_mm);

  const CellCollisionGeometry& g_;
  planner::CellKinematics kin_;
  Eigen::Matrix<double, 8, 1> weight_;  // per axis: lever of the nozzle (arm) or of the part's box (positioner), mm
  double radius_mm_ = 0.0, half_mm_ = 0.0;
  double contact_mm_, probe_mm_, tolerance_mm_;
  double certified_;
  double deepest_ = 0.0;
  std::size_t queries_ = 0, poses_ = 0;
  std::vector<Eigen::Isometry3d> X_WL_;
};

}  // namespace waam::twin
