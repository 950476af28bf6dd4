// The order of a layer's islands (or passes): as planned, round robin, or the one deposited longest ago first
// (path.island_order), to spread the heat of layers with several blades, fins or rib-web passes.
#pragma once

#include <cstddef>

#include "planner/path/pattern_names.h"
#include "planner/path/tool_path.h"
#include "planner/timeline/timeline.h"

namespace waam::planner {

// What OrderIslands did.
struct IslandOrderReport {
  std::size_t layers_reordered = 0;  // layers whose units were visited in another order than planned
  std::size_t max_units = 0;         // most units (islands, else passes) of one layer
};

// Reorders the passes of every layer of `plan` (part frame P, mm), which must not have its retracts yet (a layer's
// points are passes: an arc-off point followed by weld points; AddRetracts rebuilds the travel afterwards). The units
// of a layer are its islands -- the passes whose first weld point lies in one region of the layer's slice -- when
// the slice has several regions holding passes, else its single passes; a unit's passes keep their order.
//  - kAsPlanned: nothing changes.
//  - kRoundRobin: layer l visits its units in planned order starting at unit l mod n, so consecutive layers with the
//    same units start at different ones.
//  - kCoolestFirst: the unit whose island was last deposited longest ago first. An island is followed from layer to
//    layer by its weld points' centroid (a unit matches the nearest earlier island whose centroid lies within its
//    bounding box grown by two bead widths; none: a new island, never deposited, first). The time is a proxy from
//    `timing`: the arc time of every pass (arc start + weld length over speed + arc end) and straight travel at the
//    rapid speed between passes, without the cell's accelerations or any wait (a temperature is not computed here).
// Layers entered by a weld move (a spiral continuing its pass) and layers with fewer than two units are left as
// they are; arc-off points between passes (a planner's own travel points) are dropped in reordered layers only.
// Deterministic (ties keep the planned order).
IslandOrderReport OrderIslands(IslandOrder order, const TimelineSettings& timing, Plan* plan);

}  // namespace waam::planner
