// Dynamic programming over layers for the torch's spin (see cell_resolve.h).
#include "twin/cell/cell_resolve.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/numbers.h"
#include "models/core/parallel.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {
namespace {

// One layer at one spin value: the violating samples and the smallest margin (scaled so 1 is comfortable).
struct LayerScore {
  double bad = 0.0;
  double margin = std::numeric_limits<double>::infinity();
};

std::vector<LayerScore> ScoreLayers(const CellModel& cell, const planner::CellKinematics& kin,
                                    const std::vector<planner::CellSample>& motion, std::size_t layers,
                                    const std::vector<int>& layer_of_sample, const CellSettings& settings) {
  std::vector<LayerScore> scores(layers);
  const double margin_rad = settings.joint_margin_deg / kDeg;
  Eigen::Matrix<double, 8, 1> max_speed;
  max_speed << kin.arm.max_speed, kin.positioner.tilt_max_speed, kin.positioner.rotation_max_speed;
  std::vector<std::size_t> first(layers, motion.size()), count(layers, 0);
  for (std::size_t i = 0; i < motion.size(); ++i) {
    const auto l = static_cast<std::size_t>(layer_of_sample[i]);
    first[l] = std::min(first[l], i);
    ++count[l];
  }
  CellState state(cell);
  std::vector<CellContact> contacts;
  for (std::size_t i = 0; i < motion.size(); ++i) {
    const planner::CellSample& s = motion[i];
    LayerScore& score = scores[static_cast<std::size_t>(layer_of_sample[i])];
    if (!s.reachable) {
      score.bad += 1.0;
      score.margin = std::min(score.margin, -1.0);
      continue;
    }
    double arm_margin = std::numeric_limits<double>::infinity();
    for (int j = 0; j < 6; ++j) arm_margin = std::min({arm_margin, s.q[j] - kin.arm.lower[j], kin.arm.upper[j] - s.q[j]});
    const double j5_deg = J5Deg(s.q);
    bool bad = arm_margin < margin_rad || j5_deg < settings.singularity_deg;
    if (s.weld && i > 0 && s.dt_s > 0.0 && motion[i - 1].reachable) {
      const Eigen::Matrix<double, 8, 1> v = (s.q - motion[i - 1].q).cwiseAbs() / s.dt_s;
      bad = bad || (v.array() > max_speed.array()).any();
    }
    score.margin = std::min({score.margin, (arm_margin - margin_rad) * kDeg / 10.0,
                             (j5_deg - settings.singularity_deg) / 10.0});
    // Collisions between cell bodies on a subsample of the layer.
    const std::size_t l = static_cast<std::size_t>(layer_of_sample[i]);
    const std::size_t stride = std::max<std::size_t>(1, count[l] / kResolveCollisionSamples);
    if ((i - first[l]) % stride == 0) {
      state.SetJoints(s.q);
      contacts.clear();
      double clearance = 0.0;
      const int n = state.Collide(settings.collision_tolerance_mm, &contacts, &clearance);
      if (n > 0) bad = true;
      score.margin = std::min(score.margin, clearance / CellModel::kClearanceMarginMm);
    }
    if (bad) score.bad += 1.0;
  }
  return scores;
}

}  // namespace

std::vector<double> ResolveLayerSpins(const CellModel& cell, const planner::CellKinematics& kin,
                                      const planner::Plan& plan, const planner::MotionOptions& options,
                                      const CellSettings& settings) {
  const std::size_t layers = plan.layers.size();
  if (layers == 0) return {};
  const double range = settings.torch.spin_range_deg;
  const double step = settings.torch.spin_step_deg;
  std::vector<double> spins;  // rad, from -range to +range
  const int half = static_cast<int>(std::floor(range / step + 1e-9));
  for (int k = -half; k <= half; ++k) spins.push_back(k * step / kDeg);
  const std::size_t n = spins.size();

  // The layer of each sample (the motion lists the layers in plan order).
  std::vector<double> layer_length(layers, 0.0);
  std::vector<bool> welded_entry(layers, false);
  const planner::PathPoint* prev = nullptr;
  for (std::size_t l = 0; l < layers; ++l) {
    const planner::LayerPath& layer = plan.layers[l];
    welded_entry[l] = prev != nullptr && !layer.points.empty() && layer.points.front().weld;
    for (const planner::PathPoint& p : layer.points) {
      if (prev) layer_length[l] += (p.p_P - prev->p_P).norm();
      prev = &p;
    }
  }

  // Scores per spin value (in parallel), then per layer.
  std::vector<std::vector<LayerScore>> scores(n);
  ParallelFor(n, [&](std::size_t k) {
    planner::MotionOptions o = options;
    o.layer_spin_rad.assign(layers, spins[k]);
    const std::vector<planner::CellSample> motion = planner::PlanCellMotion(kin, plan, o, {});
    std::vector<int> layer_of_sample(motion.size());
    std::size_t l = 0;
    for (std::size_t i = 0; i < motion.size(); ++i) {
      while (l + 1 < layers && plan.layers[l].index != motion[i].layer) ++l;
      layer_of_sample[i] = static_cast<int>(l);
    }
    scores[k] = ScoreLayers(cell, kin, motion, layers, layer_of_sample, settings);
  });

  // Dynamic programming over the layers.
  const auto cost = [&](std::size_t l, std::size_t k) {
    const LayerScore& s = scores[k][l];
    const double margin = std::isfinite(s.margin) ? std::clamp(s.margin, 0.0, 1.0) : 1.0;
    return s.bad + 0.5 * (1.0 - margin) + 1e-4 * std::abs(spins[k]);
  };
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> total(layers, std::vector<double>(n, kInf));
  std::vector<std::vector<int>> from(layers, std::vector<int>(n, -1));
  for (std::size_t k = 0; k < n; ++k) total[0][k] = cost(0, k);
  for (std::size_t l = 1; l < layers; ++l) {
    const double max_change = welded_entry[l] ? settings.torch.max_spin_deg_per_mm / kDeg * layer_length[l] : kInf;
    for (std::size_t k = 0; k < n; ++k) {
      for (std::size_t j = 0; j < n; ++j) {
        const double change = std::abs(spins[k] - spins[j]);
        if (change > max_change + 1e-12 || !std::isfinite(total[l - 1][j])) continue;
        const double t = total[l - 1][j] + 0.01 * change;
        if (t < total[l][k]) {
          total[l][k] = t;
          from[l][k] = static_cast<int>(j);
        }
      }
      if (std::isfinite(total[l][k])) total[l][k] += cost(l, k);
    }
  }
  std::size_t best = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (total[layers - 1][k] < total[layers - 1][best]) best = k;
  }
  std::vector<double> chosen(layers, 0.0);
  for (std::size_t l = layers; l-- > 0;) {
    chosen[l] = spins[best];
    if (l > 0 && from[l][best] >= 0) best = static_cast<std::size_t>(from[l][best]);
  }
  return chosen;
}

}  // namespace waam::twin
