// Top-surface measures of the simulated part: height map, section profiles, waviness, Ra and boundary lag.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "planner/geometry/polygon.h"
#include "twin/deposition/voxel_grid.h"

namespace waam::twin {

// Height of the top surface over the XY plane: one cell per voxel column, NaN where no metal was deposited.
struct HeightMap {
  int i0 = 0;                  // voxel index of the first column along x
  int j0 = 0;                  // along y
  int nx = 0;
  int ny = 0;
  double voxel_mm = 0.0;
  std::vector<float> top_mm;   // nx * ny, row-major in y (index (j - j0) * nx + (i - i0)), mm above z = 0

  bool Contains(int i, int j) const { return i >= i0 && j >= j0 && i < i0 + nx && j < j0 + ny; }
  // Top height of column (i, j), NaN outside the map or where it is empty.
  double At(int i, int j) const;
  // Top height at the column containing the point (x, y) in mm.
  double AtPoint(const Eigen::Vector2d& p_mm) const;
  // Centre of column (i, j) in mm.
  Eigen::Vector2d ColumnCenter(int i, int j) const { return {(i + 0.5) * voxel_mm, (j + 0.5) * voxel_mm}; }
};

// Scans the grid from above: the top of the highest occupied voxel of every column.
HeightMap TopHeightMap(const VoxelGrid& grid);

// One sample of a section line: distance along the line (mm) and top height (mm, NaN where no metal).
struct ProfileSample {
  double s_mm = 0.0;
  double z_mm = 0.0;
};

// Samples the top height along the straight section line p0 -> p1 (mm) every `step_mm` (> 0; 0 = one voxel).
std::vector<ProfileSample> SectionProfile(const HeightMap& map, const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                                          double step_mm = 0.0);

// Waviness: the largest peak-to-valley of the heights (DIN EN ISO 4287 W_t as 003 sec. 4.2 uses it), mm; NaN-free
// samples only; 0 for fewer than two samples.
double Waviness(const std::vector<ProfileSample>& profile);

// Arithmetic mean roughness Ra = 1/n sum |h_i - mean h| (Ding et al. eq. 7) over the given heights, mm.
double ArithmeticRoughness(const std::vector<double>& heights_mm);

// Heights of the columns inside `region` (part frame XY, mm) at least `margin_mm` from its outline.
std::vector<double> RegionHeights(const HeightMap& map, const std::vector<planner::PolygonWithHoles>& region,
                                  double margin_mm);

// Boundary lag (003 Fig. 23-24): mean top height of the interior (columns more than 1.5 w from the outline) minus
// the mean top height along the outer bead (columns w/4 to 3w/4 from the outline, around its centre line), mm.
// Positive when the boundary is lower. `bead_width_mm` > 0. A part with no column 1.5 w from its outline (a thin
// wall, a rib-web) has no interior to compare with: the lag and interior mean are then NaN (null in JSON).
struct BoundaryLag {
  double interior_mean_mm = 0.0;  // NaN without interior columns
  double boundary_mean_mm = 0.0;  // NaN without boundary columns
  double lag_mm = 0.0;            // NaN unless both were measured
  std::size_t interior_columns = 0;
  std::size_t boundary_columns = 0;
};
// Over every column of `region`; if `section` has two points, only the columns the section line p0 -> p1 crosses.
BoundaryLag MeasureBoundaryLag(const HeightMap& map, const std::vector<planner::PolygonWithHoles>& region,
                               double bead_width_mm, const std::vector<Eigen::Vector2d>& section = {});

// Distance from `p` to the nearest outline (outer ring or hole) of `region`, mm.
double DistanceToOutline(const std::vector<planner::PolygonWithHoles>& region, const Eigen::Vector2d& p);
// True if `p` is inside an outer ring of `region` and outside its holes.
bool InsideRegion(const std::vector<planner::PolygonWithHoles>& region, const Eigen::Vector2d& p);

}  // namespace waam::twin
