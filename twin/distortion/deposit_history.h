// What the distortion model needs to know of the deposition: layer, build direction and heat input of every voxel.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "planner/path/tool_path.h"
#include "planner/scenario/simulation_settings.h"
#include "twin/deposition/bead_deposition.h"

namespace waam::twin {

// The deposition history of a twin build: the bead table and the travel speed along every executed pass.
class DepositHistory {
 public:
  // From the plan the depositor executed (same `settings` and `rapid_speed_mm_s` > 0, so pass i is bead i) and the
  // wire feed of the process (`wire_feed_mm_s` > 0). Throws InputError if the plan and the bead table disagree.
  DepositHistory(const planner::Plan& plan, const Depositor& depositor, const planner::SimulationSettings& settings,
                 double rapid_speed_mm_s, double wire_feed_mm_s);

  int layers() const { return static_cast<int>(layer_dir_.size()); }
  double wire_feed_mm_s() const { return wire_feed_mm_s_; }
  // Layer of bead `bead` (the layer its pass started in).
  int LayerOfBead(std::uint32_t bead) const { return bead_layer_[bead]; }
  // Plan layer of the metal bead `bead` laid at build time `time_s`: a continuous spiral is one pass that climbs
  // through every layer, and each of its loops belongs to its own layer.
  int LayerAt(std::uint32_t bead, double time_s) const;
  // Build direction (unit) and mean planned bead height (mm) of layer `layer`.
  const Eigen::Vector3d& LayerDir(int layer) const { return layer_dir_[layer]; }
  double LayerHeight(int layer) const { return layer_height_[layer]; }
  // Travel speed (mm/s) of bead `bead` where it laid metal at build time `time_s` (the voxel's deposition time).
  double SpeedAt(std::uint32_t bead, double time_s) const;

 private:
  struct PassTiming {
    std::vector<double> time_s;   // deposition time the depositor gives metal laid at each executed point
    std::vector<double> speed_mm_s;
    std::vector<int> layer;        // plan layer of the segment ending at each executed point
  };
  std::vector<int> bead_layer_;
  std::vector<PassTiming> passes_;
  std::vector<Eigen::Vector3d> layer_dir_;
  std::vector<double> layer_height_;
  double wire_feed_mm_s_;
};

}  // namespace waam::twin
