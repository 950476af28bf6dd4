// The part deposited so far as a height map over the part frame's xy plane, for torch-to-part collision checks.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace waam::twin {

// Top height of deposited metal on a regular grid in the part frame P (valid for layers built along +z of P): the
// metal is a vertical column below the height stored at each grid point.
class DepositMap {
 public:
  // Covers [min_xy, max_xy] (mm) with square cells of `cell_mm` (> 0).
  DepositMap(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy, double cell_mm);

  // Lays a bead from a to b (part frame, mm; the TCP path, the bead top at the TCP height) of width `width_mm`.
  // The bead is rasterised when a query first needs the grid (most queries are answered by top_mm() alone).
  void Deposit(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double width_mm);

  // Deepest penetration (mm, 0 if none) of a capsule from a to b (part frame, mm) of radius r (mm) into the metal.
  double Penetration(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius_mm) const;

  // Lower bound on the distance (mm, 0 when they touch) between the capsule from a to b (part frame, mm) of radius
  // r (mm) and the metal, capped at `cap_mm` (> 0): columns farther than that are not looked at.
  double Distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius_mm, double cap_mm) const;

  // No metal lies above this height (mm; very negative while nothing is deposited).
  double top_mm() const { return top_; }

 private:
  struct Bead {
    Eigen::Vector3d a, b;
    double width_mm;
  };
  int Index(int ix, int iy) const { return iy * nx_ + ix; }
  // The highest metal over the tiles that hold grid points x0..x1, y0..y1 (kTile x kTile points a tile).
  float TileTop(int x0, int x1, int y0, int y1) const;
  void Rasterise(const Bead& bead) const;
  void Flush() const;
  Eigen::Vector2d origin_;
  double cell_;
  int nx_ = 0;
  int ny_ = 0;
  mutable std::vector<float> height_;
  int tiles_x_ = 0;
  mutable std::vector<float> tile_top_;  // per tile of kTile x kTile grid points: the highest metal in it, mm
  mutable std::vector<Bead> pending_;  // laid, not yet rasterised
  double top_;
};

}  // namespace waam::twin
