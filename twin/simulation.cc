// MeasureBuild: the virtual scanner over a deposited part (deviation, voids, section profiles, Ra, boundary lag).
#include "twin/simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <utility>

#include "models/core/error.h"
#include "twin/scanner/target_volume.h"

namespace waam::twin {
namespace {

// Lowest and highest corner of the outer outlines of `region` (infinite when it is empty), mm.
std::pair<Eigen::Vector2d, Eigen::Vector2d> BoundingBox(const std::vector<planner::PolygonWithHoles>& region) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const planner::PolygonWithHoles& r : region) {
    for (const Eigen::Vector2d& p : r.outer) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  return {lo, hi};
}

// Largest peak-to-valley of the top heights along the x and y lines through the centre of the region's bounding box,
// sampled only inside the region and at least `margin_mm` from its outline.
double SectionWaviness(const HeightMap& map, const std::vector<planner::PolygonWithHoles>& region, double margin_mm) {
  const auto [lo, hi] = BoundingBox(region);
  if (!std::isfinite(lo.x())) return 0.0;
  const Eigen::Vector2d c = 0.5 * (lo + hi);
  double worst = 0.0;
  for (const auto& [p0, p1] : {std::pair{Eigen::Vector2d(lo.x(), c.y()), Eigen::Vector2d(hi.x(), c.y())},
                               std::pair{Eigen::Vector2d(c.x(), lo.y()), Eigen::Vector2d(c.x(), hi.y())}}) {
    std::vector<ProfileSample> kept;
    const double length = (p1 - p0).norm();
    for (const ProfileSample& s : SectionProfile(map, p0, p1)) {
      const Eigen::Vector2d p = p0 + (p1 - p0) * (length > 0 ? s.s_mm / length : 0.0);
      if (InsideRegion(region, p) && DistanceToOutline(region, p) >= margin_mm) {
        kept.push_back({s.s_mm, std::isnan(s.z_mm) ? 0.0 : s.z_mm});
      }
    }
    worst = std::max(worst, Waviness(kept));
  }
  return worst;
}

// The boundary lag of 003 Fig. 24 like its profilometer: along the x and y section lines through the middle of the
// top layer's region, pooled over both lines.
BoundaryLag MeasureTopBoundaryLag(const HeightMap& top, const std::vector<planner::PolygonWithHoles>& top_region,
                                  double bead_width_mm) {
  BoundaryLag lag;
  const auto [lo, hi] = BoundingBox(top_region);
  if (std::isfinite(lo.x())) {
    const Eigen::Vector2d c = 0.5 * (lo + hi);
    const BoundaryLag along_x = MeasureBoundaryLag(top, top_region, bead_width_mm,
                                                   {Eigen::Vector2d(lo.x(), c.y()), Eigen::Vector2d(hi.x(), c.y())});
    const BoundaryLag along_y = MeasureBoundaryLag(top, top_region, bead_width_mm,
                                                   {Eigen::Vector2d(c.x(), lo.y()), Eigen::Vector2d(c.x(), hi.y())});
    lag.interior_columns = along_x.interior_columns + along_y.interior_columns;
    lag.boundary_columns = along_x.boundary_columns + along_y.boundary_columns;
    // Column-weighted means of the two lines; a line without columns of a kind adds nothing (its mean is NaN).
    auto pooled = [](double mean_x, std::size_t n_x, double mean_y, std::size_t n_y) {
      if (n_x + n_y == 0) return std::numeric_limits<double>::quiet_NaN();
      return ((n_x > 0 ? mean_x * n_x : 0.0) + (n_y > 0 ? mean_y * n_y : 0.0)) / (n_x + n_y);
    };
    lag.interior_mean_mm = pooled(along_x.interior_mean_mm, along_x.interior_columns, along_y.interior_mean_mm,
                                  along_y.interior_columns);
    lag.boundary_mean_mm = pooled(along_x.boundary_mean_mm, along_x.boundary_columns, along_y.boundary_mean_mm,
                                  along_y.boundary_columns);
    lag.lag_mm = lag.interior_mean_mm - lag.boundary_mean_mm;  // NaN on thin walls: no interior to compare
  }
  return lag;
}

// Waviness, Ra and the top height of a planar build over its top layer's region (w/2 in from its outline), into `m`.
void MeasureTopSurface(const HeightMap& top, const std::vector<planner::PolygonWithHoles>& top_region,
                       double bead_width_mm, TwinMeasures& m) {
  m.waviness_mm = SectionWaviness(top, top_region, 0.5 * bead_width_mm);
  const std::vector<double> heights = RegionHeights(top, top_region, 0.5 * bead_width_mm);
  m.ra_mm = ArithmeticRoughness(heights);
  m.top_mean_mm = m.top_min_mm = m.top_max_mm = std::numeric_limits<double>::quiet_NaN();
  if (!heights.empty()) {
    const auto [lo_h, hi_h] = std::minmax_element(heights.begin(), heights.end());
    m.top_min_mm = *lo_h;
    m.top_max_mm = *hi_h;
    m.top_mean_mm = std::accumulate(heights.begin(), heights.end(), 0.0) / heights.size();
  }
  m.boundary_lag = MeasureTopBoundaryLag(top, top_region, bead_width_mm);
}

}  // namespace

std::string TopSurfaceNotApplicable(const planner::Plan& plan) {
  if (plan.layers.empty() || plan.layers.back().slice.empty()) {
    return "the top layer has no sliced region (an imported program): no top surface to measure";
  }
  const double kMaxTilt = std::cos(1.0 * M_PI / 180.0);
  for (const planner::LayerPath& layer : plan.layers) {
    std::ostringstream why;
    if (layer.build_dir_P.normalized().z() < kMaxTilt) {
      why << "multi-directional part: layer " << layer.index << " grows along (" << layer.build_dir_P.x() << ", "
          << layer.build_dir_P.y() << ", " << layer.build_dir_P.z()
          << "), not +z; top-surface measures of a planar build do not apply";
      return why.str();
    }
    if (!layer.slice_in_plane || !layer.slice_axes_P.isApprox(Eigen::Matrix<double, 3, 2>::Identity(), 1e-6)) {
      why << "non-planar part: layer " << layer.index
          << " is not a horizontal plane; top-surface measures of a planar build do not apply";
      return why.str();
    }
    double z_lo = std::numeric_limits<double>::infinity(), z_hi = -z_lo, bead_h = 0.0;
    for (const planner::PathPoint& p : layer.points) {
      if (!p.weld) continue;
      z_lo = std::min(z_lo, p.p_P.z());
      z_hi = std::max(z_hi, p.p_P.z());
      bead_h = std::max(bead_h, p.bead_height_mm);
    }
    if (z_hi - z_lo > 1.5 * bead_h) {  // a spiral layer ramps by one layer height
      why << "non-planar part: the weld points of layer " << layer.index << " span " << (z_hi - z_lo)
          << " mm in z; top-surface measures of a planar build do not apply";
      return why.str();
    }
  }
  return "";
}

TwinResult MeasureBuild(const planner::Plan& plan, Depositor depositor, const planner::TriangleMesh* target,
                        double bead_width_mm) {
  WAAM_THROW_UNLESS(bead_width_mm > 0.0, "simulate: bead width = " << bead_width_mm << " mm: must be > 0");
  TwinResult result{std::move(depositor), {}, {}, {}, {}};
  const twin::SimulationSettings& settings = result.depositor.settings();
  TwinMeasures& m = result.measures;
  m.deposition_s = result.depositor.deposition_wall_s();
  const VoxelGrid& grid = result.depositor.grid();
  m.voxel_mm = grid.voxel_mm();
  m.layers = plan.layers.size();
  m.beads = result.depositor.beads().size();
  m.voxels = grid.occupied();
  m.weld_length_mm = result.depositor.weld_length_mm();
  m.build_time_s = result.depositor.build_time_s();
  m.deposited_volume_mm3 = grid.OccupiedVolume();
  m.expected_volume_mm3 = result.depositor.expected_volume_mm3();
  m.grid_memory_bytes = grid.MemoryBytes();

  // The virtual scanner.
  result.top = TopHeightMap(grid);
  m.top_surface_not_applicable = TopSurfaceNotApplicable(plan);
  if (!m.top_surface_not_applicable.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    m.waviness_mm = m.ra_mm = m.top_mean_mm = m.top_min_mm = m.top_max_mm = nan;
    m.boundary_lag.lag_mm = m.boundary_lag.interior_mean_mm = m.boundary_lag.boundary_mean_mm = nan;
  } else {
    MeasureTopSurface(result.top, plan.layers.back().slice, bead_width_mm, m);
  }
  if (target != nullptr && !target->facets.empty()) {
    result.deviation = MeasureDeviation(grid, *target);
    result.voids = FindVoids(grid, TargetVolume::FromMesh(*target, grid.voxel_mm(), settings.max_voxels),
                             settings.min_void_volume_mm3);
  } else if (std::any_of(plan.layers.begin(), plan.layers.end(),
                         [](const planner::LayerPath& layer) { return !layer.slice.empty(); })) {
    // Without a target mesh the sliced regions are the target; an imported program has none (no voids measured).
    result.voids = FindVoids(grid, TargetVolume::FromLayers(plan, grid.voxel_mm(), settings.max_voxels),
                             settings.min_void_volume_mm3);
  }
  return result;
}

}  // namespace waam::twin
