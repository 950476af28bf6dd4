// Deposit history: the executed passes re-timed the way the depositor stamps its voxels.
#include "twin/distortion/deposit_history.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/error.h"
#include "twin/deposition/executed_path.h"
#include "twin/scanner/point_hash.h"

namespace waam::twin {
namespace {

constexpr double kCellMm = 4.0;  // cell of the segment hash, mm

}  // namespace

DepositHistory::DepositHistory(const planner::Plan& plan, const Depositor& depositor,
                               const twin::SimulationSettings& settings, double rapid_speed_mm_s,
                               double wire_feed_mm_s)
    : wire_feed_mm_s_(wire_feed_mm_s) {
  WAAM_THROW_UNLESS(wire_feed_mm_s > 0.0, "distortion: wire feed " << wire_feed_mm_s << " mm/s: must be > 0");
  const std::vector<ExecutedPass> passes = ExecutePlan(plan, settings, rapid_speed_mm_s);
  WAAM_THROW_UNLESS(passes.size() == depositor.beads().size(),
                    "distortion: the plan has " << passes.size() << " weld passes but the deposit "
                    << depositor.beads().size() << " beads: they must come from the same plan and settings");
  int max_layer = 0;
  for (const planner::LayerPath& layer : plan.layers) max_layer = std::max(max_layer, layer.index);
  for (const BeadRecord& bead : depositor.beads()) max_layer = std::max(max_layer, bead.layer);
  layer_dir_.assign(max_layer + 1, Eigen::Vector3d::UnitZ());
  layer_height_.assign(max_layer + 1, 0.0);
  for (const planner::LayerPath& layer : plan.layers) {
    layer_dir_[layer.index] = layer.build_dir_P.normalized();
    double sum = 0.0;
    int n = 0;
    for (const planner::PathPoint& p : layer.points) {
      if (!p.weld) continue;
      sum += p.bead_height_mm;
      ++n;
    }
    layer_height_[layer.index] = n > 0 ? sum / n : 0.0;
  }
  for (const BeadRecord& bead : depositor.beads()) bead_layer_.push_back(bead.layer);
  // The depositor stamps metal laid at arc length s of move k with start + T_(k-1) + (s - s_(k-1)) / v_k
  // (PassTimes).
  passes_.reserve(passes.size());
  for (std::size_t b = 0; b < passes.size(); ++b) {
    const ExecutedPass& pass = passes[b];
    PassTiming t;
    const std::vector<double> times = PassTimes(pass);
    for (std::size_t k = 0; k < pass.points.size(); ++k) {
      const ExecutedPoint& p = pass.points[k];
      t.time_s.push_back(pass.start_time_s + times[k]);
      t.speed_mm_s.push_back(p.speed_mm_s > 0.0 ? p.speed_mm_s : pass.points.back().speed_mm_s);
      t.layer.push_back(p.layer);  // the plan layer of the move ending here (a spiral runs through many)
    }
    // Segment windows: the depositor stamps metal laid by segment k between start + T_(k-1) and start + T_k.
    for (std::size_t k = 1; k < pass.points.size(); ++k) {
      const ExecutedPoint& a = pass.points[k - 1];
      const ExecutedPoint& e = pass.points[k];
      Segment seg{a.p_P, e.p_P, pass.start_time_s + times[k - 1], pass.start_time_s + times[k],
                  static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(k)};
      // Every cell a voxel of this segment's bead can lie in: the box of the segment grown by the bead's reach.
      const double reach = e.bead_width_mm * std::max(1.0, e.width_factor) + 2.0 * e.bead_height_mm + 1.0;
      const Eigen::Vector3d lo = a.p_P.cwiseMin(e.p_P).array() - reach;
      const Eigen::Vector3d hi = a.p_P.cwiseMax(e.p_P).array() + reach;
      const Eigen::Vector3i clo = CellOf(lo, kCellMm);
      const Eigen::Vector3i chi = CellOf(hi, kCellMm);
      for (int z = clo.z(); z <= chi.z(); ++z) {
        for (int y = clo.y(); y <= chi.y(); ++y) {
          for (int x = clo.x(); x <= chi.x(); ++x) {
            cells_[CellKey(Eigen::Vector3i(x, y, z))].push_back(static_cast<std::uint32_t>(segments_.size()));
          }
        }
      }
      segments_.push_back(seg);
    }
    passes_.push_back(std::move(t));
  }
  grid_ = &depositor.grid();
  voxels_.reserve(grid_->occupied());
  grid_->ForEach([&](const VoxelIndex& v, const VoxelData& d) {
    voxels_.push_back(At(d.bead, d.time_s, grid_->Center(v)));
  });
}

VoxelDeposit DepositHistory::At(std::uint32_t bead, double time_s, const Eigen::Vector3d& p_P) const {
  WAAM_THROW_UNLESS(bead < passes_.size(), "distortion: voxel of bead " << bead << " but the history has "
                                                                        << passes_.size() << " passes");
  const PassTiming& t = passes_[bead];
  // The stamp times are stored as float, so a stamp at a segment's end falls in the next segment's window too: the
  // time selects the candidates, the position the segment.
  const double tolerance = 1e-3 + 1e-6 * std::abs(time_s);
  // Segments whose window holds the time are tested first (a spiral's cell holds a segment of every loop, about 200
  // per voxel on part I, and at most a few share the window); only if none does, the nearest of all. Same result as
  // ranking every candidate by distance with the out-of-window ones last, without their distances.
  std::uint32_t k = 0;
  auto it = cells_.find(CellKey(CellOf(p_P, kCellMm)));
  if (it != cells_.end()) {
    auto distance = [&](const Segment& seg) {
      const Eigen::Vector3d ab = seg.b - seg.a;
      const double len2 = ab.squaredNorm();
      const double u = len2 > 0.0 ? std::clamp((p_P - seg.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      return (p_P - (seg.a + u * ab)).norm();
    };
    for (const bool windowed : {true, false}) {
      double best = std::numeric_limits<double>::infinity();
      for (std::uint32_t i : it->second) {
        const Segment& seg = segments_[i];
        if (seg.pass != bead) continue;
        const bool in_window = time_s >= std::min(seg.t0, seg.t1) - tolerance &&
                               time_s <= std::max(seg.t0, seg.t1) + tolerance;
        if (windowed && !in_window) continue;
        const double d = distance(seg);
        if (d < best) {
          best = d;
          k = seg.index;
        }
      }
      if (k != 0) break;
    }
  }
  if (k == 0) {
    // Not near any segment of its pass (cannot happen for the depositor's voxels): the time alone.
    auto at = std::lower_bound(t.time_s.begin(), t.time_s.end(), time_s);
    k = at == t.time_s.end() ? static_cast<std::uint32_t>(t.time_s.size() - 1)
                             : static_cast<std::uint32_t>(at - t.time_s.begin());
    if (k == 0 && t.time_s.size() > 1) k = 1;
  }
  return {t.speed_mm_s[k], t.layer[k]};
}

const std::vector<VoxelDeposit>& DepositHistory::Voxels(const VoxelGrid& grid) const {
  WAAM_DEMAND(&grid == grid_ && grid.occupied() == voxels_.size());  // the depositor's grid, unchanged since
  return voxels_;
}

double DepositHistory::SpeedAt(std::uint32_t bead, double time_s) const {
  const PassTiming& t = passes_[bead];
  auto it = std::lower_bound(t.time_s.begin(), t.time_s.end(), time_s);
  std::size_t k = it == t.time_s.end() ? t.time_s.size() - 1 : static_cast<std::size_t>(it - t.time_s.begin());
  if (k == 0 && t.speed_mm_s.size() > 1) k = 1;  // the first point starts the pass; its speed is unused
  return t.speed_mm_s[k];
}

}  // namespace waam::twin
