// Bead deposition into the voxel grid: each bead section is swept along the executed pass and its material, area x
// length, fills the lowest free voxels under the footprint up to the parabolic cap (material is conserved).
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "planner/path/tool_path.h"
#include "twin/simulation_settings.h"
#include "twin/deposition/executed_path.h"
#include "twin/deposition/torch_columns.h"
#include "twin/deposition/voxel_grid.h"

namespace waam {
class Progress;
}

namespace waam::twin {

// What the twin knows about one deposited bead (one weld pass).
struct BeadRecord {
  int layer = 0;
  double length_mm = 0.0;                // executed path length, mm
  double expected_volume_mm3 = 0.0;      // integral of the section area along the pass, mm^3
  double deposited_volume_mm3 = 0.0;     // voxels occupied by this bead x voxel volume, mm^3
  double start_time_s = 0.0;             // arc start, s from the start of the build
  // A pass that runs on into later layers (a spiral): (time from the start of the build, s; layer) where each
  // later layer begins. Empty for a pass within one layer.
  std::vector<std::pair<float, int>> layer_starts;
};

// Checks the settings; throws InputError naming the `simulation.<key>` that is out of range.
void ValidateSimulationSettings(const twin::SimulationSettings& settings);

// The deposition twin: a const model (settings) and the growing part (grid and bead table).
class Depositor {
 public:
  // Throws InputError for invalid settings (see ValidateSimulationSettings).
  explicit Depositor(const twin::SimulationSettings& settings);

  // Deposits one executed pass and returns its bead index. Throws InputError when the grid's voxel limit is passed.
  std::uint32_t DepositPass(const ExecutedPass& pass);

  const VoxelGrid& grid() const { return grid_; }
  const std::vector<BeadRecord>& beads() const { return beads_; }
  const twin::SimulationSettings& settings() const { return settings_; }
  double expected_volume_mm3() const { return expected_volume_mm3_; }
  double weld_length_mm() const { return weld_length_mm_; }
  // Time of the build from its start to the arc end of the last deposited pass (weld and travel), s.
  double build_time_s() const { return build_time_s_; }
  // Wall-clock time spent in DepositPass so far, s.
  double deposition_wall_s() const { return deposition_wall_s_; }
  // Layer of an occupied voxel: its bead's, or for a pass through several layers the layer it was laid in
  // (by the voxel's deposition time).
  int LayerOf(const VoxelData& data) const;

 private:
  struct Column;
  struct Segment;
  struct PassFill;
  class StepFill;
  internal::TorchFrame HoldFrame(const ExecutedPoint& A, const ExecutedPoint& B);
  Segment SegmentColumns(const ExecutedPass& pass, std::size_t i, const internal::TorchFrame& frame) const;
  void FillSegment(const ExecutedPass& pass, const Segment& segment, const internal::TorchFrame& frame,
                   PassFill& fill);
  double FillStep(std::vector<Column>& columns, const BeadSection& section, double target_mm3, double zeta_tcp_mm,
                  const internal::TorchFrame& frame, const VoxelData& data, bool last_step, double drape);

  twin::SimulationSettings settings_;
  VoxelGrid grid_;
  std::vector<BeadRecord> beads_;
  double expected_volume_mm3_ = 0.0;
  double weld_length_mm_ = 0.0;
  double build_time_s_ = 0.0;
  double deposition_wall_s_ = 0.0;
  std::vector<internal::ColumnVoxel> column_voxels_;  // scratch of FillStep: the voxels of one step's columns
  std::optional<internal::TorchFrame> held_frame_;    // the lattice of the last segment (see DepositPass)
};

// The one function that deposits a plan: executes it (travel timed at `rapid_speed_mm_s`, > 0) and deposits every
// pass in order. `progress` (may be null) gets the number of passes as its total and counts them. Throws InputError
// for invalid settings or past the voxel limit.
Depositor DepositPlan(const planner::Plan& plan, const twin::SimulationSettings& settings,
                      double rapid_speed_mm_s, Progress* progress);

}  // namespace waam::twin
