// The dispatcher over the slicing types, and the part's mesh from the loaded STL bytes or a generator.
#include "planner/plan_scenario.h"

#include "models/core/error.h"
#include "planner/cone_planner.h"
#include "planner/mesh/generators.h"
#include "planner/mesh/stl_io.h"
#include "planner/multidir_planner.h"
#include "planner/path/retract.h"
#include "planner/skeleton_planner.h"
#include "planner/timeline/island_order.h"

namespace waam::planner {
namespace {

// The plan with the planners' own arc-off moves (straight, on the layer).
PlanResult PlanWithoutRetracts(const PlannerSections& scenario, Progress* progress) {
  switch (scenario.slicing.type) {
    case SlicingType::kCone:
    case SlicingType::kCylinder: return PlanConeScenario(scenario, progress);
    case SlicingType::kMultiDirectional: return PlanMultiDirectionalScenario(scenario, progress);
    case SlicingType::kSkeleton: return PlanSkeletonScenario(scenario, progress);
    case SlicingType::kPlanar: break;
  }
  return PlanPlanarScenario(scenario, progress);
}

}  // namespace

TriangleMesh PartMesh(const PartSpec& part, double weld_tolerance_mm, MeshReport* report) {
  TriangleMesh mesh;
  if (!part.mesh_path.empty()) {
    // The scenario loader reads the file; a scenario built in code without its bytes is the caller's mistake.
    WAAM_DEMAND(part.mesh_data != nullptr);
    mesh = ParseStl(*part.mesh_data, part.mesh_path, weld_tolerance_mm, report);
  } else {
    WAAM_THROW_UNLESS(part.generator, part.where << ": give exactly one of 'mesh' or 'generator'");
    mesh = GeneratePart(*part.generator, part.params, part.where);
    *report = InspectMesh(mesh, weld_tolerance_mm, std::string(NameOf(*part.generator)));
  }
  CheckSliceable(*report);
  return mesh;
}

PlanResult PlanScenario(const PlannerSections& scenario, Progress* progress) {
  PlanResult result = PlanWithoutRetracts(scenario, progress);
  const TimelineSettings timing = TimelineSettingsOf(scenario.process);
  // The islands' order (path.island_order) before the travel between passes is built.
  OrderIslands(scenario.path.island_order, timing, &result.plan);
  result.retract = AddRetracts(scenario.path.retract_mm, &result.plan);
  result.stats = ComputeStats(result.plan);
  // Without the cell: arc-off moves at the rapid speed (analysis::AddCellTimeline times them on the cell's axes).
  result.timeline = BuildTimeline(result.plan, {}, AxisLimits{}, timing);
  result.stats.estimated_time_s = result.timeline.total_s;
  return result;
}

}  // namespace waam::planner
