// Redundancy resolution: the torch's rotation about its own axis (the weld does not see it) chosen per layer so that
// the arm keeps away from its joint limits, the wrist singularity, its axis speeds and collisions.
#pragma once

#include <cstddef>
#include <vector>

#include "planner/kinematics/cell_motion.h"
#include "planner/path/tool_path.h"
#include "twin/cell/cell_settings.h"

namespace waam::twin {

class CellModel;

// Per layer of `plan`: the torch's spin about its axis (rad) that `cell.resolve: optimise` chooses.
//
// Method: dynamic programming over layers. The spin takes the values -spin_range ... +spin_range at spin_step. For
// each value the whole path's motion is computed with that spin (PlanCellMotion, the IK branch kept continuous as in
// the fixed rule) and each layer is scored: the samples that would be violations (unreachable, an arm joint within
// the joint margin, |J5| within the singularity margin, a joint faster than its limit while welding, and contacts
// between cell bodies detected on up to kResolveCollisionSamples samples of the layer), then the smallest margin
// min(arm joint margin excess / 10 deg, |J5| excess / 10 deg, clearance / 10 mm). A layer's cost is its violating
// samples plus (1 - margin) / 2 (margin clamped to [0, 1]); changing the spin between layers costs 0.01 per rad and
// is not allowed faster than max_spin_deg_per_mm over a layer entered by a weld move (the spin changes along that
// layer; over an arc-off move into a layer it may change freely, the move is slowed to the axis speeds). Among equal
// costs the smaller |spin| wins, so a path the fixed rule already serves keeps spin 0. The IK branch is not searched:
// it follows from continuity as in the fixed rule. Weld points and tool axes are not changed.
//
// `kin` is the cell's kinematics with the part placed, `options` the motion options of the check (step, rapid speed,
// positioner rule); the layers' scores are computed in parallel over spin values, each with its own CellState.
std::vector<double> ResolveLayerSpins(const CellModel& cell, const planner::CellKinematics& kin,
                                      const planner::Plan& plan, const planner::MotionOptions& options,
                                      const CellSettings& settings);

// Most samples per layer and spin value the resolution runs collision detection on.
inline constexpr std::size_t kResolveCollisionSamples = 24;

}  // namespace waam::twin
