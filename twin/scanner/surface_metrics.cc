// Top-surface measures: height map from the voxel columns, profiles along section lines, W_t, Ra (Ding eq. 7) and
// the boundary lag of the dissertation's block experiment (003 sec. 3.4, Fig. 24).
#include "twin/scanner/surface_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "models/core/error.h"

namespace waam::twin {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

double SegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double RingDistance(const planner::Ring& ring, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < ring.size(); ++i) {
    best = std::min(best, SegmentDistance(p, ring[i], ring[(i + 1) % ring.size()]));
  }
  return best;
}

}  // namespace

double HeightMap::At(int i, int j) const {
  if (!Contains(i, j)) return std::numeric_limits<double>::quiet_NaN();
  return top_mm[static_cast<std::size_t>(j - j0) * nx + (i - i0)];
}

double HeightMap::AtPoint(const Eigen::Vector2d& p) const {
  return At(static_cast<int>(std::floor(p.x() / voxel_mm)), static_cast<int>(std::floor(p.y() / voxel_mm)));
}

HeightMap TopHeightMap(const VoxelGrid& grid) {
  HeightMap map;
  map.voxel_mm = grid.voxel_mm();
  VoxelIndex lo, hi;
  if (!grid.Bounds(&lo, &hi)) return map;
  map.i0 = lo.x();
  map.j0 = lo.y();
  map.nx = hi.x() - lo.x() + 1;
  map.ny = hi.y() - lo.y() + 1;
  map.top_mm.assign(static_cast<std::size_t>(map.nx) * map.ny, kNaN);
  grid.ForEach([&](const VoxelIndex& v, const VoxelData&) {
    float& top = map.top_mm[static_cast<std::size_t>(v.y() - map.j0) * map.nx + (v.x() - map.i0)];
    const float z = static_cast<float>((v.z() + 1) * map.voxel_mm);
    if (std::isnan(top) || z > top) top = z;
  });
  return map;
}

std::vector<ProfileSample> SectionProfile(const HeightMap& map, const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                                          double step_mm) {
  WAAM_THROW_UNLESS(step_mm >= 0.0, "section profile: step = " << step_mm << " mm: must be >= 0");
  const double step = step_mm > 0.0 ? step_mm : map.voxel_mm;
  const double length = (p1 - p0).norm();
  std::vector<ProfileSample> profile;
  if (step <= 0.0) return profile;
  const int n = static_cast<int>(std::floor(length / step));
  for (int k = 0; k <= n; ++k) {
    const double s = k * step;
    const Eigen::Vector2d p = length > 0.0 ? Eigen::Vector2d(p0 + (p1 - p0) * (s / length)) : p0;
    profile.push_back({s, map.AtPoint(p)});
  }
  return profile;
}

double Waviness(const std::vector<ProfileSample>& profile) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const ProfileSample& s : profile) {
    if (std::isnan(s.z_mm)) continue;
    lo = std::min(lo, s.z_mm);
    hi = std::max(hi, s.z_mm);
  }
  return hi >= lo ? hi - lo : 0.0;
}

// Ding et al. eq. 7: Ra = (1/n) sum |h_i - h_mean|.
double ArithmeticRoughness(const std::vector<double>& heights) {
  if (heights.empty()) return 0.0;
  const double mean = std::accumulate(heights.begin(), heights.end(), 0.0) / heights.size();
  double sum = 0.0;
  for (double h : heights) sum += std::abs(h - mean);
  return sum / heights.size();
}

double DistanceToOutline(const std::vector<planner::PolygonWithHoles>& region, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const planner::PolygonWithHoles& r : region) {
    best = std::min(best, RingDistance(r.outer, p));
    for (const planner::Ring& hole : r.holes) best = std::min(best, RingDistance(hole, p));
  }
  return best;
}

bool InsideRegion(const std::vector<planner::PolygonWithHoles>& region, const Eigen::Vector2d& p) {
  for (const planner::PolygonWithHoles& r : region) {
    if (!planner::PointInRing(p, r.outer)) continue;
    bool in_hole = false;
    for (const planner::Ring& hole : r.holes) in_hole = in_hole || planner::PointInRing(p, hole);
    if (!in_hole) return true;
  }
  return false;
}

std::vector<double> RegionHeights(const HeightMap& map, const std::vector<planner::PolygonWithHoles>& region,
                                  double margin_mm) {
  std::vector<double> heights;
  for (int j = map.j0; j < map.j0 + map.ny; ++j) {
    for (int i = map.i0; i < map.i0 + map.nx; ++i) {
      const Eigen::Vector2d c = map.ColumnCenter(i, j);
      if (!InsideRegion(region, c) || DistanceToOutline(region, c) < margin_mm) continue;
      const double z = map.At(i, j);
      heights.push_back(std::isnan(z) ? 0.0 : z);  // an empty column inside the region is a hole down to z = 0
    }
  }
  return heights;
}

BoundaryLag MeasureBoundaryLag(const HeightMap& map, const std::vector<planner::PolygonWithHoles>& region,
                               double bead_width_mm, const std::vector<Eigen::Vector2d>& section) {
  WAAM_THROW_UNLESS(bead_width_mm > 0.0, "boundary lag: bead width = " << bead_width_mm << " mm: must be > 0");
  WAAM_THROW_UNLESS(section.empty() || section.size() == 2,
                    "boundary lag: a section line needs 2 points, got " << section.size());
  const double w = bead_width_mm;
  BoundaryLag lag;
  double interior_sum = 0.0;
  double boundary_sum = 0.0;
  auto visit = [&](const Eigen::Vector2d& c, double z) {
    if (!InsideRegion(region, c)) return;
    const double d = DistanceToOutline(region, c);
    if (std::isnan(z)) z = 0.0;
    if (d >= 1.5 * w) {
      interior_sum += z;
      ++lag.interior_columns;
    } else if (d >= 0.25 * w && d <= 0.75 * w) {
      boundary_sum += z;
      ++lag.boundary_columns;
    }
  };
  if (section.size() == 2) {
    for (const ProfileSample& s : SectionProfile(map, section[0], section[1])) {
      const double len = (section[1] - section[0]).norm();
      const Eigen::Vector2d p = section[0] + (section[1] - section[0]) * (len > 0.0 ? s.s_mm / len : 0.0);
      visit(p, s.z_mm);
    }
  } else {
    for (int j = map.j0; j < map.j0 + map.ny; ++j) {
      for (int i = map.i0; i < map.i0 + map.nx; ++i) visit(map.ColumnCenter(i, j), map.At(i, j));
    }
  }
  constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();
  lag.interior_mean_mm = lag.interior_columns > 0 ? interior_sum / lag.interior_columns : kNotMeasured;
  lag.boundary_mean_mm = lag.boundary_columns > 0 ? boundary_sum / lag.boundary_columns : kNotMeasured;
  lag.lag_mm = lag.interior_mean_mm - lag.boundary_mean_mm;  // NaN when either side has no column
  return lag;
}

}  // namespace waam::twin
