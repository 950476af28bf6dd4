// The planar planning pipeline: scenario -> mesh -> slices -> one path per layer -> statistics.
#pragma once

#include "planner/mesh/triangle_mesh.h"
#include "planner/path/tool_path.h"
#include "planner/scenario/scenario.h"

namespace waam {
class Progress;
}

namespace waam::planner {

// Everything `waam plan` produces in memory; the analysis module writes it to plan.json, plan.h5 and PNGs.
struct PlanResult {
  TriangleMesh mesh;       // the part, welded, in the part frame (mm); the substrate top is z = 0
  MeshReport mesh_report;
  Plan plan;
  PathStats stats;
};

// Loads or generates the part, slices it at the scenario's layer height and plans every layer with the scenario's
// pattern. Throws InputError for a mesh that cannot be sliced or settings that cannot be planned.
// `progress` may be null.
PlanResult PlanScenario(const Scenario& scenario, Progress* progress);

}  // namespace waam::planner
