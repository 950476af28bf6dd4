// Multi-axis deposition: a straight single-bead wall built with the torch and the build direction tilted off z grows
// along the torch axis with side walls as flat as the voxels allow (the bead is swept in the torch frame).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "tests/twin/twin_settings.h"
#include "models/core/numbers.h"
#include "tests/twin/test_paths.h"
#include "twin/deposition/bead_deposition.h"

namespace waam::twin {
namespace {

constexpr double kVoxel = 0.5;     // mm
constexpr int kLayers = 16;
constexpr double kDz = 1.3;        // layer step along b, mm (a 6 x 2 mm bead, 8 mm^2, on a 6-8 mm wall grows ~1.1 mm)

// The wall frame: x along the wall, b the build direction (tilted `tilt_deg` from z towards the wall's normal), n the
// normal; the whole wall turned `yaw_deg` about z.
struct WallFrame {
  Eigen::Vector3d x, b, n;
  WallFrame(double tilt_deg, double yaw_deg) {
    const double t = tilt_deg * kPi / 180.0;
    const Eigen::Matrix3d R_yaw = Eigen::AngleAxisd(yaw_deg * kPi / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    x = R_yaw * Eigen::Vector3d::UnitX();
    b = R_yaw * Eigen::Vector3d(0.0, std::sin(t), std::cos(t));
    n = R_yaw * Eigen::Vector3d(0.0, std::cos(t), -std::sin(t));
  }
};

// Side-wall measures: one profile of the outermost metal along b per voxel-wide row across x, on each side.
struct SideWall {
  double ra_mm = 0.0;             // mean over profiles of the mean |residual| about the profile's least-squares line
  double wt_mm = 0.0;             // mean over profiles of the peak-to-valley about that line
  double width_mm = 0.0;          // mean distance between the two side faces along n
  double lean_deg = 0.0;          // mean angle of the side lines off b (0: the wall grows along the torch axis)
  double deviation_mm = 0.0;      // mean |distance| of the side faces from the ideal wall: the reference half width
  double max_deviation_mm = 0.0;  // either side of the plane through the path along b; and its largest value
  double volume_error = 0.0;      // (deposited - expected) / expected
  int pinholes = 0;               // empty voxels enclosed by metal on all six faces
};

// Empty voxels (above the substrate) whose six face neighbours are all metal: voxel-scale pinholes the fill left
// inside the part.
int CountPinholes(const VoxelGrid& grid) {
  VoxelIndex lo, hi;
  if (!grid.Bounds(&lo, &hi)) return 0;
  int count = 0;
  for (int i = lo.x(); i <= hi.x(); ++i) {
    for (int j = lo.y(); j <= hi.y(); ++j) {
      for (int k = std::max(0, lo.z()); k <= hi.z(); ++k) {
        const VoxelIndex v(i, j, k);
        if (grid.Occupied(v)) continue;
        int solid = 0;
        for (int a = 0; a < 3; ++a) {
          for (int s : {-1, 1}) solid += grid.Solid(v + s * VoxelIndex::Unit(a)) ? 1 : 0;
        }
        count += solid == 6 ? 1 : 0;
      }
    }
  }
  return count;
}

twin::SimulationSettings Settings() {
  twin::SimulationSettings s = twin::TestSimulationSettings();
  s.voxel_mm = kVoxel;
  return s;
}

// A straight wall 60 mm along x, kLayers layers kDz apart along b, torch along b, one pass per layer alternating
// direction, 6 x 2 mm beads.
planner::Plan TiltedWall(const WallFrame& f) {
  planner::Plan plan;
  for (int k = 0; k < kLayers; ++k) {
    planner::LayerPath layer;
    layer.index = k;
    for (int i = 0; i < 2; ++i) {
      const double s = (k % 2 == 0) == (i == 0) ? 0.0 : 60.0;
      const Eigen::Vector3d p = s * f.x + (k + 1) * kDz * f.b;
      planner::PathPoint point = testing::Pt(p.x(), p.y(), p.z(), i > 0, 6.0, 2.0, 8.0);
      point.tool_dir_P = f.b;
      layer.points.push_back(point);
    }
    layer.z_mm = layer.points.front().p_P.z();
    plan.layers.push_back(layer);
  }
  return plan;
}

// Measures the side walls between 15 and 45 mm along x (clear of the start and stop shapes), from 4 mm up b (clear of
// the foot on the substrate) to 5 mm below the wall's top (clear of the rounded crown). The outermost voxel centre is
// taken per half-millimetre band of b.
SideWall MeasureSideWall(const Depositor& d, const WallFrame& f, double half_width_mm) {
  constexpr double kBand = 0.5;
  constexpr double kBottom = 4.0;
  const double v = d.grid().voxel_mm();
  double top = kBottom;
  d.grid().ForEach([&](const VoxelIndex& idx, const VoxelData&) {
    const Eigen::Vector3d c = d.grid().Center(idx);
    if (c.dot(f.x) >= 15.0 && c.dot(f.x) <= 45.0) top = std::max(top, c.dot(f.b));
  });
  const double b_hi = kBottom + kBand * std::floor((top - 5.0 - kBottom) / kBand);  // whole bands only
  std::map<std::pair<int, int>, std::pair<double, double>> extent;  // (row, band) -> (min n, max n)
  d.grid().ForEach([&](const VoxelIndex& idx, const VoxelData&) {
    const Eigen::Vector3d c = d.grid().Center(idx);
    const double cx = c.dot(f.x);
    const double cb = c.dot(f.b);
    if (cx < 15.0 || cx > 45.0 || cb < kBottom || cb >= b_hi) return;
    const auto key = std::make_pair(static_cast<int>(std::floor(cx / v)), static_cast<int>(std::floor((cb - kBottom) / kBand)));
    const double cn = c.dot(f.n);
    auto [it, inserted] = extent.emplace(key, std::make_pair(cn, cn));
    if (!inserted) {
      it->second.first = std::min(it->second.first, cn);
      it->second.second = std::max(it->second.second, cn);
    }
  });
  std::map<int, std::vector<std::pair<double, std::pair<double, double>>>> rows;  // row -> (band centre, (min, max))
  for (const auto& [key, mm] : extent) rows[key.first].push_back({kBottom + (key.second + 0.5) * kBand, mm});
  SideWall out;
  int profiles = 0, samples_n = 0;
  for (const auto& [row, samples] : rows) {
    for (int side = 0; side < 2; ++side) {
      auto outer = [&](const std::pair<double, double>& mm) { return side == 0 ? mm.first : mm.second; };
      double sb = 0, sn = 0, sbb = 0, sbn = 0;
      const double m = static_cast<double>(samples.size());
      for (const auto& [cb, mm] : samples) {
        sb += cb, sn += outer(mm), sbb += cb * cb, sbn += cb * outer(mm);
      }
      const double slope = (m * sbn - sb * sn) / (m * sbb - sb * sb);
      const double icpt = (sn - slope * sb) / m;
      double ra = 0.0, lo = 1e9, hi = -1e9;
      for (const auto& [cb, mm] : samples) {
        const double r = outer(mm) - (icpt + slope * cb);
        ra += std::abs(r);
        lo = std::min(lo, r);
        hi = std::max(hi, r);
        const double off = std::abs(std::abs(outer(mm)) + 0.5 * v - half_width_mm);
        out.deviation_mm += off;
        out.max_deviation_mm = std::max(out.max_deviation_mm, off);
        ++samples_n;
      }
      out.ra_mm += ra / m;
      out.wt_mm += hi - lo;
      out.lean_deg += std::atan(slope) * 180.0 / kPi;
      ++profiles;
    }
    for (const auto& [cb, mm] : samples) out.width_mm += (mm.second - mm.first + v) / samples.size();
  }
  out.ra_mm /= profiles;
  out.wt_mm /= profiles;
  out.lean_deg /= profiles;
  out.width_mm /= rows.size();
  out.deviation_mm /= samples_n;
  out.volume_error = (d.grid().OccupiedVolume() - d.expected_volume_mm3()) / d.expected_volume_mm3();
  out.pinholes = CountPinholes(d.grid());
  return out;
}

SideWall BuildAndMeasure(double tilt_deg, double yaw_deg, double half_width_mm) {
  const WallFrame f(tilt_deg, yaw_deg);
  const Depositor d = DepositPlan(TiltedWall(f), Settings(), 100.0, nullptr);
  const SideWall s = MeasureSideWall(d, f, half_width_mm);
  std::printf("wall tilted %4.1f deg (yaw %4.1f): side Ra %.3f mm, W_t %.3f mm, width %.2f mm, lean %+.2f deg, "
              "off the ideal wall mean %.3f max %.3f mm, volume %+.3f %%, %d pinholes\n", tilt_deg, yaw_deg, s.ra_mm,
              s.wt_mm, s.width_mm, s.lean_deg, s.deviation_mm, s.max_deviation_mm, 100.0 * s.volume_error,
              s.pinholes);
  return s;
}

// The ideal tilted wall is the vertical wall turned about its path: the footprint columns run along the torch axis, so
// the layers stack along b (not as vertical column stacks that drift off it, a staircase). Left: voxel noise, i.e.
// a plane's staircase through a 0.5 mm grid.
TEST(TiltedWall, GrowsAlongTheTorchAxisWithFlatSides) {
  const SideWall vertical = BuildAndMeasure(0.0, 0.0, 4.0);  // its own reference: 6 mm beads make an 8 mm wall
  EXPECT_NEAR(vertical.volume_error, 0.0, 0.02);
  const double half_width = 0.5 * vertical.width_mm;
  for (const auto& [tilt, yaw] : std::vector<std::pair<double, double>>{{20, 0}, {40, 0}, {40, 30}, {50, 0}}) {
    const SideWall tilted = BuildAndMeasure(tilt, yaw, half_width);
    EXPECT_NEAR(tilted.volume_error, 0.0, 0.02) << "deposited volume must equal the bead area x length";
    EXPECT_LT(std::abs(tilted.lean_deg), 2.0) << "the " << tilt << " deg wall must grow along the torch axis";
    EXPECT_LT(tilted.deviation_mm, 0.5 * kVoxel)
        << "side faces of the " << tilt << " deg wall off the vertical wall turned about its path (half width "
        << half_width << " mm)";
    EXPECT_LT(tilted.max_deviation_mm, 2.0 * kVoxel) << "largest side-face offset of the " << tilt << " deg wall";
    EXPECT_LT(tilted.ra_mm, vertical.ra_mm + 0.5 * kVoxel)
        << "side-wall Ra of the " << tilt << " deg wall, vertical wall " << vertical.ra_mm << " mm";
    EXPECT_LE(tilted.pinholes, vertical.pinholes + 10) << "voxel pinholes left inside the " << tilt << " deg wall";
  }
}

// A wall bent like a tube's side: the torch turns 2.5 deg about the path from one layer to the next (0 to 37.5 deg),
// so every layer lies on the previous one through a differently turned lattice. The seams leave no pinholes in the
// part and the volume balances.
TEST(TiltedWall, TorchTurningBetweenLayersLeavesNoPinholes) {
  planner::Plan plan;
  Eigen::Vector3d o = Eigen::Vector3d::Zero();
  for (int k = 0; k < kLayers; ++k) {
    const WallFrame f(2.5 * k, 0.0);
    o += kDz * f.b;
    planner::LayerPath layer;
    layer.index = k;
    for (int i = 0; i < 2; ++i) {
      const double s = (k % 2 == 0) == (i == 0) ? 0.0 : 60.0;
      const Eigen::Vector3d p = s * f.x + o;
      planner::PathPoint point = testing::Pt(p.x(), p.y(), p.z(), i > 0, 6.0, 2.0, 8.0);
      point.tool_dir_P = f.b;
      layer.points.push_back(point);
    }
    layer.z_mm = o.z();
    plan.layers.push_back(layer);
  }
  const Depositor d = DepositPlan(plan, Settings(), 100.0, nullptr);
  const int pinholes = CountPinholes(d.grid());
  const double error = (d.grid().OccupiedVolume() - d.expected_volume_mm3()) / d.expected_volume_mm3();
  std::printf("wall turning 2.5 deg per layer: %d pinholes in %zu voxels, volume %+.3f %%\n", pinholes,
              d.grid().occupied(), 100.0 * error);
  EXPECT_NEAR(error, 0.0, 0.02) << "deposited volume must equal the bead area x length";
  EXPECT_LT(pinholes, 0.001 * d.grid().occupied()) << "voxel pinholes left between turned layers";
}

}  // namespace
}  // namespace waam::twin
