// Deposit history: the executed passes re-timed the way the depositor stamps its voxels.
#include "twin/distortion/deposit_history.h"

#include <Eigen/Geometry>
#include <algorithm>

#include "models/core/error.h"
#include "twin/deposition/executed_path.h"

namespace waam::twin {

DepositHistory::DepositHistory(const planner::Plan& plan, const Depositor& depositor,
                               const planner::SimulationSettings& settings, double rapid_speed_mm_s,
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
  // The depositor stamps metal laid at arc length s of a pass with time start + s / v (v: speed of the segment).
  passes_.reserve(passes.size());
  for (const ExecutedPass& pass : passes) {
    PassTiming t;
    double running = pass.start_time_s;
    for (const ExecutedPoint& p : pass.points) {
      const double v = std::max(p.speed_mm_s, 1e-9);
      running = std::max(running, pass.start_time_s + p.s_mm / v);  // kept monotonic for the search
      t.time_s.push_back(running);
      t.speed_mm_s.push_back(p.speed_mm_s > 0.0 ? p.speed_mm_s : pass.points.back().speed_mm_s);
    }
    passes_.push_back(std::move(t));
  }
}

double DepositHistory::SpeedAt(std::uint32_t bead, double time_s) const {
  const PassTiming& t = passes_[bead];
  auto it = std::lower_bound(t.time_s.begin(), t.time_s.end(), time_s);
  std::size_t k = it == t.time_s.end() ? t.time_s.size() - 1 : static_cast<std::size_t>(it - t.time_s.begin());
  if (k == 0 && t.speed_mm_s.size() > 1) k = 1;  // the first point starts the pass; its speed is unused
  return t.speed_mm_s[k];
}

}  // namespace waam::twin
