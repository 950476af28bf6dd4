// The nozzle against the deposited part between the samples (conservative advancement after Mirtich 1996, as
// twin/cell/cell_sweep.cc for the cell's bodies): the distance bound from the deposit map, the approach bound from the
// axes' travel times their levers, forward kinematics between samples from the geometry's body tree.
#include "twin/cell/deposit_sweep.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "planner/kinematics/positioner.h"
#include "twin/cell/cell_sweep.h"

namespace waam::twin {
namespace {

constexpr int kMaxDepthProbes = 64;

}  // namespace

DepositSweep::DepositSweep(const CellModel& cell, const CellCollisionGeometry& geometry,
                           const planner::CellKinematics& kin, const Eigen::AlignedBox3d& part_box_P, double contact_mm,
                           double probe_mm, double tolerance_mm)
    : g_(geometry), kin_(kin), contact_mm_(contact_mm), probe_mm_(probe_mm), tolerance_mm_(tolerance_mm),
      certified_(std::numeric_limits<double>::infinity()) {
  Eigen::Vector3d a_T, b_T;
  cell.NozzleInTcp(&a_T, &b_T, &radius_mm_);
  half_mm_ = 0.5 * (b_T - a_T).norm();
  // The arm moves the nozzle (its levers); the positioner moves the part: a point x of it lies |x_C.xy| from the
  // rotation axis (z of the table frame C) and at most |p_AC| + |x_C| from the tilt axis (x of A through its
  // origin); the largest over the part's box is at a corner (both are convex in x).
  weight_ = g_.nozzle_lever_mm;
  weight_[6] = weight_[7] = 0.0;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d x_C =
        kin.positioner.X_CP * part_box_P.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
    weight_[7] = std::max(weight_[7], x_C.head<2>().norm());
    weight_[6] = std::max(weight_[6], kin.positioner.p_AC.norm() + x_C.norm());
  }
}

NozzleInPart DepositSweep::PoseAt(const planner::Joints8& q) {
  ++poses_;
  LinkPosesAt(g_, q, &X_WL_);
  const Eigen::Isometry3d X_PN =
      (kin_.X_WB * planner::PartPose(kin_.positioner, q[6], q[7])).inverse() * X_WL_[g_.nozzle_link] * g_.X_LN;
  return {X_PN * Eigen::Vector3d(0.0, 0.0, -half_mm_), X_PN * Eigen::Vector3d(0.0, 0.0, half_mm_)};
}

double DepositSweep::Bound(const NozzleInPart& n, const DepositMap& deposit, double cap_mm) {
  ++queries_;
  return deposit.Distance(n.a_P, n.b_P, radius_mm_, cap_mm);
}

std::optional<DepositContact> DepositSweep::Move(const planner::CellSample& a, const NozzleInPart& n_a,
                                                 const planner::CellSample& b, const NozzleInPart& n_b,
                                                 const DepositMap& deposit) {
  const double M = weight_.dot((b.q - a.q).cwiseAbs());
  // The nozzle's lowest points above the deposit's top: free, and enough far above the part.
  const double top = deposit.top_mm();
  const double above_a = std::min(n_a.a_P.z(), n_a.b_P.z()) - radius_mm_ - top;
  const double above_b = std::min(n_b.a_P.z(), n_b.b_P.z()) - radius_mm_ - top;
  double bound = IntervalBound(above_a, above_b, M);
  if (std::min(above_a, above_b) > contact_mm_ && bound > contact_mm_) {
    certified_ = std::min(certified_, bound);
    return std::nullopt;
  }
  // The deposit map's bounds at the ends, looking as far as the move can approach.
  const double cap = M + 1.0;
  const double d_b = Bound(n_b, deposit, cap);
  double f = 0.0, d = Bound(n_a, deposit, cap);
  bound = IntervalBound(d, d_b, M);
  if (std::min(d, d_b) > contact_mm_ && bound > contact_mm_) {
    certified_ = std::min(certified_, bound);
    return std::nullopt;
  }
  // Advance within the move: every axis's travel is linear in the fraction f, so M (1 - f) is left.
  const auto joints = [&](double at) { return planner::Joints8(a.q + at * (b.q - a.q)); };
  while (d > contact_mm_) {
    const double next = f + (d - 0.5 * contact_mm_) / M;
    if (next >= 1.0) {
      certified_ = std::min(certified_, IntervalBound(d, d_b, (1.0 - f) * M));
      return std::nullopt;
    }
    const double d_next = Bound(PoseAt(joints(next)), deposit, cap);
    certified_ = std::min(certified_, IntervalBound(d, d_next, (next - f) * M));
    f = next;
    d = d_next;
  }
  certified_ = std::min(certified_, d);
  // Within contact_mm at f: MuJoCo-free probes of the depth through the rest of the move, the end sample included.
  const int n = std::clamp(static_cast<int>(std::ceil((1.0 - f) * M / probe_mm_)), 1, kMaxDepthProbes);
  double deepest = deposit.Penetration(n_b.a_P, n_b.b_P, radius_mm_);
  for (int k = 0; k < n; ++k) {
    const NozzleInPart at = PoseAt(joints(f + (1.0 - f) * k / n));
    deepest = std::max(deepest, deposit.Penetration(at.a_P, at.b_P, radius_mm_));
  }
  if (deepest <= tolerance_mm_) return std::nullopt;
  deepest_ = std::max(deepest_, deepest);
  return DepositContact{a.t_s + f * (b.t_s - a.t_s), f > 0.0 && f < 1.0, deepest};
}

}  // namespace waam::twin
