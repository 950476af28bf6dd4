// The part deposited so far as a height map over the part frame's xy plane, for torch-to-part collision checks.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace waam::twin {

// Top height of deposited metal on a regular grid in the part frame P (valid for layers built along +z of P).
class DepositMap {
 public:
  // Covers [min_xy, max_xy] (mm) with square cells of `cell_mm` (> 0).
  DepositMap(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy, double cell_mm);

  // Lays a bead from a to b (part frame, mm; the TCP path, the bead top at the TCP height) of width `width_mm`.
  void Deposit(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double width_mm);

  // Deepest penetration (mm, 0 if none) of a capsule from a to b (part frame, mm) of radius r (mm) into the metal.
  double Penetration(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius_mm) const;

  double top_mm() const { return top_; }

 private:
  int Index(int ix, int iy) const { return iy * nx_ + ix; }
  Eigen::Vector2d origin_;
  double cell_;
  int nx_ = 0;
  int ny_ = 0;
  std::vector<float> height_;
  double top_;
};

}  // namespace waam::twin
