// The planar planning pipeline: the part's mesh, sliced, each layer planned, the result counted.
#include "planner/planar_planner.h"

#include <cmath>
#include <mutex>

#include "models/core/error.h"
#include "models/bead/parabolic_bead.h"
#include "models/core/numbers.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "planner/geometry/simplify.h"
#include "planner/plan_scenario.h"
#include "planner/path/layer_pattern.h"
#include "planner/plan_limits.h"
#include "planner/slicing/planar_slicer.h"

namespace waam::planner {
namespace {

constexpr double kWeldToleranceMm = 1e-4;

// Puts the part on the substrate: its lowest point at z = 0 (the part frame's origin plane).
void PlaceOnSubstrate(TriangleMesh* mesh, MeshReport* report) {
  if (mesh->vertices.empty()) return;
  double z_min = mesh->vertices.front().z();
  for (const Eigen::Vector3d& v : mesh->vertices) z_min = std::min(z_min, v.z());
  if (z_min == 0.0) return;
  for (Eigen::Vector3d& v : mesh->vertices) v.z() -= z_min;
  report->bbox_min.z() -= z_min;
  report->bbox_max.z() -= z_min;
}

}  // namespace

PatternOptions PatternOptionsFor(const PlannerSections& scenario, double bead_width_mm) {
  PatternOptions options;
  options.pattern = scenario.path.pattern;
  options.bead_width_mm = bead_width_mm;
  options.overlap_model = scenario.path.overlap_model;
  options.zigzag_auto = scenario.path.zigzag_angle_auto;
  options.zigzag_angle_rad = scenario.path.zigzag_angle_deg * kPi / 180.0;
  options.alternate_start = scenario.path.alternate_start;
  options.seed = scenario.path.seed;
  options.contour_tolerance_mm = kContourToleranceFraction * bead_width_mm;
  return options;
}

void SetVolumeBalanceBead(const PlannerSections& scenario, PlanResult* result) {
  const ProcessSettings& process = scenario.process;
  result->travel_speed_mm_min = process.travel_speed_mm_min;
  result->bead_width_mm = scenario.path.bead_width_mm;
  result->bead_area_mm2 = models::BeadAreaFromWireFeed(process.wire_diameter_mm, process.wire_feed_mm_min,
                                                       process.travel_speed_mm_min, process.deposition_efficiency);
  result->bead_height_mm = 1.5 * result->bead_area_mm2 / result->bead_width_mm;
  result->layer_growth_mm =
      result->bead_area_mm2 / OverlapSpacingFor(scenario.path.overlap_model, result->bead_width_mm).zigzag_mm;
}

namespace {

// The bead of planar layers `layer_height` (mm) high: either the scenario's speed and width with the height from the
// wire-feed volume balance, or the speed for the layer height and the width that comes with it from the fitted models
// (sec. 6.3.2.1, eq. 6.6-6.7). Overlapping beads at the zigzag spacing l grow a layer by A / l; when that differs
// from the slicing step, the twin shows the part ending high or low, as a real build would.
void SetPlanarBead(const PlannerSections& scenario, double layer_height, PlanResult* result) {
  const ProcessSettings& process = scenario.process;
  result->layer_height_mm = layer_height;
  if (process.bead_model != BeadModel::kSpeedHeight) {
    SetVolumeBalanceBead(scenario, result);
    return;
  }
  WAAM_DEMAND(process.speed_height != nullptr && process.width_height != nullptr);
  const models::BeadSetpoint setpoint =
      models::SetpointForHeight(*process.speed_height, *process.width_height, layer_height);
  result->travel_speed_mm_min = setpoint.speed.speed_mm_per_min;
  result->bead_width_mm = setpoint.width_mm;
  result->speed_clamp = models::ToString(setpoint.speed.clamp);
  result->bead_height_mm = setpoint.speed.achieved_mm;
  result->bead_area_mm2 = models::ParabolicBead{result->bead_width_mm, result->bead_height_mm}.Area();
  result->layer_growth_mm =
      result->bead_area_mm2 / OverlapSpacingFor(scenario.path.overlap_model, result->bead_width_mm).zigzag_mm;
}

// Each layer's moves, with the junction void filling applied, its corner corrections and its pattern's notes.
struct PlanarLayerMoves {
  std::vector<std::vector<Move2D>> moves;
  std::vector<std::vector<CornerCorrection>> corrections;
  std::vector<std::vector<std::string>> notes;
};

// A layer's pattern depends only on its slice and its index (the start shift and any random choice are seeded by
// the index): the layers are planned in parallel, each into its own slot, so the plan is the same on any number of
// threads.
PlanarLayerMoves PlanLayerMoves(const std::vector<std::vector<PolygonWithHoles>>& slices,
                                const PatternOptions& options, const VoidFiller& void_filler, Progress* progress) {
  const std::size_t layer_count = slices.size();
  PlanarLayerMoves out;
  out.moves.resize(layer_count);
  out.corrections.resize(layer_count);
  out.notes.resize(layer_count);
  std::mutex progress_mutex;
  int layers_done = 0;
  ParallelFor(layer_count, [&](std::size_t i) {
    PatternOptions layer_options = options;
    layer_options.layer_index = static_cast<int>(i);
    out.moves[i] = void_filler.Apply(slices[i], PlanLayerPattern(slices[i], layer_options, &out.notes[i]),
                                     static_cast<int>(i), &out.corrections[i]);
    if (progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress->Update(++layers_done);
    }
  });
  return out;
}

// The path points of layer `layer` from its moves at its top z, with the result's bead and speed.
void FillPlanarPoints(const std::vector<Move2D>& moves, const PlanResult& result, LayerPath* layer) {
  const double speed_mm_s = result.travel_speed_mm_min / 60.0;
  for (const Move2D& move : moves) {
    PathPoint point;
    point.p_P = Eigen::Vector3d(move.p.x(), move.p.y(), layer->z_mm);
    point.tool_dir_P = Eigen::Vector3d::UnitZ();
    point.bead_width_mm = result.bead_width_mm;
    point.bead_height_mm = result.bead_height_mm;
    point.speed_mm_s = speed_mm_s;
    point.weld = move.weld;
    layer->points.push_back(point);
  }
}

// Appends the planned layers to `result`'s plan, their notes to its warnings and their corrections to its void
// corrections. Throws InputError (naming the part) for a layer whose pattern found no weld path where a bead fits,
// or a plan over the point limit.
void AppendPlanarLayers(const PlannerSections& scenario, const std::vector<std::vector<PolygonWithHoles>>& slices,
                        const PlanarLayerMoves& planned, PlanResult* result) {
  const int layer_count = static_cast<int>(slices.size());
  result->plan.layers.reserve(layer_count);
  std::size_t points = 0;
  for (int i = 0; i < layer_count; ++i) {
    LayerPath layer;
    layer.index = i;
    layer.z_mm = (i + 1) * result->layer_height_mm;
    layer.slice = slices[i];
    for (const std::string& note : planned.notes[i]) {
      result->warnings.push_back("layer " + std::to_string(i) + ": " + note);
    }
    result->void_corrections.insert(result->void_corrections.end(), planned.corrections[i].begin(),
                                    planned.corrections[i].end());
    WAAM_THROW_UNLESS(HasWeldOrNoRoom(layer.slice, planned.moves[i], result->bead_width_mm),
                      scenario.part.where << ": layer " << i << " (z = " << layer.z_mm << " mm): path.pattern '"
                                          << NameOf(scenario.path.pattern) << "' found no weld path in the slice of "
                                          << Area(layer.slice) << " mm^2; try path.pattern: contour");
    FillPlanarPoints(planned.moves[i], *result, &layer);
    points += layer.points.size();
    CheckPathPoints(points, i, scenario.part.where);
    result->plan.layers.push_back(std::move(layer));
  }
}

}  // namespace

PlanResult PlanPlanarScenario(const PlannerSections& scenario, Progress* progress) {
  PlanResult result;
  result.mesh = PartMesh(scenario.part, kWeldToleranceMm, &result.mesh_report);
  PlaceOnSubstrate(&result.mesh, &result.mesh_report);

  // Layer i fills [i h, (i + 1) h]; it is sliced at its mid-height and the TCP runs on its top, z = (i + 1) h.
  const double h = scenario.slicing.layer_height_mm;
  const double part_height = result.mesh_report.bbox_max.z() - result.mesh_report.bbox_min.z();
  CheckLayerCount(part_height, h, scenario.part.where);
  const int layer_count = std::max(1, static_cast<int>(std::lround(part_height / h)));
  std::vector<double> heights(layer_count);
  for (int i = 0; i < layer_count; ++i) heights[i] = (i + 0.5) * part_height / layer_count;
  if (progress) progress->SetTotal(layer_count);
  const std::vector<std::vector<PolygonWithHoles>> slices = SlicePlanar(result.mesh, heights);

  SetPlanarBead(scenario, part_height / layer_count, &result);
  const double zigzag_mm = OverlapSpacingFor(scenario.path.overlap_model, result.bead_width_mm).zigzag_mm;
  CheckWeldLengthEstimate(slices, zigzag_mm, scenario.part.where);
  const PatternOptions options = PatternOptionsFor(scenario, result.bead_width_mm);
  result.contour_tolerance_mm = options.contour_tolerance_mm;
  // Junction void filling on the planned moves; l is the spacing of the two beads of a wall (d2).
  const double l_mm = OverlapSpacingFor(scenario.path.overlap_model, result.bead_width_mm).contour_to_contour_mm;
  const VoidFiller void_filler(scenario.path.void_filling, result.bead_width_mm, l_mm);

  const PlanarLayerMoves planned = PlanLayerMoves(slices, options, void_filler, progress);
  result.plan.name = scenario.name;
  AppendPlanarLayers(scenario, slices, planned, &result);
  if (progress) progress->Finish();
  result.stats = ComputeStats(result.plan);
  result.layer_height_min_mm = result.layer_height_max_mm = result.layer_height_mm;
  result.speed_min_mm_min = result.speed_max_mm_min = result.travel_speed_mm_min;
  return result;
}

}  // namespace waam::planner
