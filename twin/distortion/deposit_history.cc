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
  // The plan layer along each pass. The passes are rebuilt from the plan as ExecutePlan splits it (a run of weld moves,
  // carried over a layer change by a continuous spiral), with the arc length at which each plan point is reached.
  struct RunPoint {
    double s_mm;
    int layer;
  };
  std::vector<std::vector<RunPoint>> runs;
  {
    std::vector<RunPoint> run;
    const planner::PathPoint* last = nullptr;
    auto flush = [&]() {
      if (run.size() >= 2 && run.back().s_mm > 0.0) runs.push_back(run);
      run.clear();
    };
    for (const planner::LayerPath& layer : plan.layers) {
      for (std::size_t i = 0; i < layer.points.size(); ++i) {
        const planner::PathPoint& p = layer.points[i];
        const planner::PathPoint* from = i > 0 ? &layer.points[i - 1] : last;
        if (from != nullptr && p.weld) {
          if (run.empty()) run.push_back({0.0, layer.index});
          run.push_back({run.back().s_mm + (p.p_P - from->p_P).norm(), layer.index});
        } else {
          flush();
        }
      }
      if (!layer.points.empty()) last = &layer.points.back();
    }
    flush();
  }
  const bool runs_match = runs.size() == passes.size();
  // The depositor stamps metal laid at arc length s of a pass with time start + s / v (v: speed of the segment).
  passes_.reserve(passes.size());
  for (std::size_t b = 0; b < passes.size(); ++b) {
    const ExecutedPass& pass = passes[b];
    PassTiming t;
    double running = pass.start_time_s;
    // Blending shortens the corners a little: the executed arc length is scaled onto the planned one.
    const double scale =
        runs_match && pass.length_mm() > 0.0 ? runs[b].back().s_mm / pass.length_mm() : 1.0;
    std::size_t r = 1;
    for (const ExecutedPoint& p : pass.points) {
      const double v = std::max(p.speed_mm_s, 1e-9);
      running = std::max(running, pass.start_time_s + p.s_mm / v);  // kept monotonic for the search
      t.time_s.push_back(running);
      t.speed_mm_s.push_back(p.speed_mm_s > 0.0 ? p.speed_mm_s : pass.points.back().speed_mm_s);
      if (!runs_match) {
        t.layer.push_back(pass.layer);
        continue;
      }
      const std::vector<RunPoint>& run = runs[b];
      while (r + 1 < run.size() && run[r].s_mm < p.s_mm * scale - 1e-9) ++r;
      t.layer.push_back(run[r].layer);
    }
    passes_.push_back(std::move(t));
  }
}

int DepositHistory::LayerAt(std::uint32_t bead, double time_s) const {
  const PassTiming& t = passes_[bead];
  auto it = std::lower_bound(t.time_s.begin(), t.time_s.end(), time_s);
  std::size_t k = it == t.time_s.end() ? t.time_s.size() - 1 : static_cast<std::size_t>(it - t.time_s.begin());
  if (k == 0 && t.layer.size() > 1) k = 1;
  return t.layer[k];
}

double DepositHistory::SpeedAt(std::uint32_t bead, double time_s) const {
  const PassTiming& t = passes_[bead];
  auto it = std::lower_bound(t.time_s.begin(), t.time_s.end(), time_s);
  std::size_t k = it == t.time_s.end() ? t.time_s.size() - 1 : static_cast<std::size_t>(it - t.time_s.begin());
  if (k == 0 && t.speed_mm_s.size() > 1) k = 1;  // the first point starts the pass; its speed is unused
  return t.speed_mm_s[k];
}

}  // namespace waam::twin
