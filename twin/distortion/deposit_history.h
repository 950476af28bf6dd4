// What the distortion model needs to know of the deposition: layer, build direction and heat input of every voxel.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "planner/path/tool_path.h"
#include "twin/simulation_settings.h"
#include "twin/deposition/bead_deposition.h"
#include "twin/deposition/voxel_grid.h"

namespace waam::twin {

// What the distortion model reads of one deposited voxel.
struct VoxelDeposit {
  double speed_mm_s = 0.0;  // travel speed of the segment that laid it, mm/s
  int layer = 0;            // plan layer of that segment
};

// The deposition history of a twin build: the bead table and the travel speed along every executed pass.
class DepositHistory {
 public:
  // From the plan the depositor executed (same `settings` and `rapid_speed_mm_s` > 0, so pass i is bead i) and the
  // wire feed of the process (`wire_feed_mm_s` > 0), after the deposit: At() of every voxel of the depositor's grid
  // is computed here, once. Throws InputError if the plan and the bead table disagree.
  DepositHistory(const planner::Plan& plan, const Depositor& depositor, const twin::SimulationSettings& settings,
                 double rapid_speed_mm_s, double wire_feed_mm_s);

  int layers() const { return static_cast<int>(layer_dir_.size()); }
  double wire_feed_mm_s() const { return wire_feed_mm_s_; }
  // Layer of bead `bead` (the layer its pass started in).
  int LayerOfBead(std::uint32_t bead) const { return bead_layer_[bead]; }
  // Speed and plan layer of the metal of bead `bead` stamped at `time_s` (s) into the voxel centred at `p_P` (mm):
  // the segment of the pass nearest to p_P among those whose stamp-time window holds time_s. A continuous spiral is
  // one pass through every layer; each of its loops belongs to its own layer.
  VoxelDeposit At(std::uint32_t bead, double time_s, const Eigen::Vector3d& p_P) const;
  // At() of every voxel of `grid` in VoxelGrid::ForEach order. `grid` must be the depositor's grid this history was
  // made from, unchanged since (WAAM_DEMAND). Const and free of caches: safe to call from many threads.
  const std::vector<VoxelDeposit>& Voxels(const VoxelGrid& grid) const;
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
  // Segment k of a pass (executed points k-1 to k) and the window of stamp times the depositor gives its metal.
  struct Segment {
    Eigen::Vector3d a, b;
    double t0 = 0.0, t1 = 0.0;
    std::uint32_t pass = 0;
    std::uint32_t index = 0;  // k
  };
  std::vector<int> bead_layer_;
  std::vector<PassTiming> passes_;
  std::vector<Eigen::Vector3d> layer_dir_;
  std::vector<double> layer_height_;
  double wire_feed_mm_s_;
  std::vector<Segment> segments_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;  // spatial hash of segments_
  const VoxelGrid* grid_ = nullptr;   // the depositor's grid, whose voxels voxels_ describes
  std::vector<VoxelDeposit> voxels_;  // At() of every voxel of grid_, in VoxelGrid::ForEach order
};

}  // namespace waam::twin
