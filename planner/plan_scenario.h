// The plan of a scenario's part: the dispatcher over the slicing types, and the part's mesh every planner starts from.
#pragma once

#include "planner/mesh/mesh_ops.h"
#include "planner/mesh/triangle_mesh.h"
#include "planner/planar_planner.h"
#include "planner/scenario/scenario.h"

namespace waam {
class Progress;
}

namespace waam::planner {

// Plans the scenario's part with the planner of its slicing.type (planar, cone/cylinder, multi-directional,
// skeleton), then orders the islands (path.island_order), rebuilds the arc-off travel (path.retract_mm) and times the
// build without the cell. The part's STL bytes and the models come with the scenario (analysis::LoadScenario).
// Throws InputError for a mesh that cannot be sliced or settings that cannot be planned. `progress` may be null.
PlanResult PlanScenario(const PlannerSections& scenario, Progress* progress);

// The part's mesh, welded at `weld_tolerance_mm`: the STL bytes the scenario loader read (part.mesh_data), or the
// generator's part; `*report` is filled and the mesh checked to be sliceable. Throws InputError naming the file or
// the generator.
TriangleMesh PartMesh(const PartSpec& part, double weld_tolerance_mm, MeshReport* report);

}  // namespace waam::planner
