// Multi-directional planar planning after Lim & Soh (seed 002): sub-volumes cut by user-given split planes, each
// planar-sliced along its build direction (the hub along the axis, each blade from its root outwards), and the
// support each needs (their Table 1).
#include "planner/multidir_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "planner/geometry/clipper_adapter.h"
#include "planner/mesh/generators.h"
#include "planner/mesh/mesh_ops.h"
#include "planner/plan_scenario.h"
#include "planner/path/layer_pattern.h"
#include "planner/slicing/centroid_decomposition.h"
#include "planner/slicing/planar_slicer.h"

namespace waam::planner {
namespace {

constexpr double kWeldToleranceMm = 1e-4;
constexpr double kFarMm = 1e5;          // half-planes are clipped as squares this large
constexpr double kMinRegionMm2 = 1.0;   // slivers along a split plane are dropped

// Rotation R_PS whose columns are the sub-volume frame S in P: z_S = the build direction.
Eigen::Matrix3d FrameFor(const Eigen::Vector3d& z) {
  const Eigen::Vector3d helper = std::abs(z.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d x = helper.cross(z).normalized();
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = z.cross(x);
  R.col(2) = z;
  return R;
}

// The half-plane a x + b y <= c of the slice plane as a large square (mm).
PolygonWithHoles HalfPlane(const Eigen::Vector2d& ab, double c) {
  const double norm = ab.norm();
  const Eigen::Vector2d m = ab / norm;
  const Eigen::Vector2d p0 = m * (c / norm);
  const Eigen::Vector2d t(-m.y(), m.x());
  Ring ring = {p0 - kFarMm * t, p0 + kFarMm * t, p0 + kFarMm * t - 2 * kFarMm * m, p0 - kFarMm * t - 2 * kFarMm * m};
  if (SignedArea(ring) < 0) std::reverse(ring.begin(), ring.end());
  return {ring, {}};
}

// The slices of one sub-volume in its frame S (z_S = its build direction `n`): R_PS, the extent [lo, hi] along n
// (the mesh's, narrowed by split planes normal to n), the layer thickness h and each layer's region inside the
// sub-volume's other split planes (slivers dropped).
struct SubVolumeSlices {
  Eigen::Matrix3d R_PS;
  double lo = 0.0, hi = 0.0, h = 0.0;
  std::vector<std::vector<PolygonWithHoles>> kept;
};

// Slices `mesh` (part frame P) for sub-volume `spec` along `n` at about `d` mm per layer. Throws InputError (`where`
// names the scenario) when the sub-volume holds no metal along its direction.
SubVolumeSlices SliceSubVolume(const TriangleMesh& mesh, const SubVolumeSpec& spec, const Eigen::Vector3d& n, double d,
                               const std::string& where) {
  SubVolumeSlices out;
  const Eigen::Matrix3d R_PS = FrameFor(n);
  out.R_PS = R_PS;
  TriangleMesh rotated = mesh;
  for (Eigen::Vector3d& v : rotated.vertices) v = R_PS.transpose() * v;
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const Eigen::Vector3d& v : rotated.vertices) {
    lo = std::min(lo, v.z());
    hi = std::max(hi, v.z());
  }
  std::vector<std::pair<Eigen::Vector3d, double>> keeps;  // in S: m . p <= c
  for (const auto& k : spec.keep) {
    const Eigen::Vector3d m = R_PS.transpose() * Eigen::Vector3d(k[0], k[1], k[2]);
    if (m.head<2>().norm() < 1e-9 * m.norm()) {
      if (m.z() < 0) lo = std::max(lo, k[3] / m.z());
      if (m.z() > 0) hi = std::min(hi, k[3] / m.z());
    } else {
      keeps.emplace_back(m, k[3]);
    }
  }
  WAAM_THROW_UNLESS(hi > lo + 0.5 * d, where << ".sub_volumes: '" << spec.name << "' holds no metal along its "
                                             << "direction (extent " << lo << " to " << hi << " mm)");
  const int count = std::max(1, static_cast<int>(std::lround((hi - lo) / d)));
  const double h = (hi - lo) / count;
  std::vector<double> heights(count);
  for (int i = 0; i < count; ++i) heights[i] = lo + (i + 0.5) * h;
  const std::vector<std::vector<PolygonWithHoles>> slices = SlicePlanar(rotated, heights);
  // The layers' regions are independent: in parallel, each into its own slot.
  out.kept.resize(count);
  ParallelFor(count, [&](std::size_t i) {
    std::vector<PolygonWithHoles> region = slices[i];
    for (const auto& [m, c] : keeps) {
      if (region.empty()) break;
      region = internal::Intersection(region, {HalfPlane(m.head<2>(), c - m.z() * heights[i])});
    }
    std::erase_if(region, [](const PolygonWithHoles& r) { return Area(r) < kMinRegionMm2; });
    out.kept[i] = std::move(region);
  });
  out.lo = lo, out.hi = hi, out.h = h;
  return out;
}

// Support (Lim & Soh Table 1), mm^3: the metal needed under each layer (regions `kept`, thickness `h` mm) so that
// everything above it stands on something when built along the direction: U_i = S_i u U_(i+1), support =
// sum (|U_i| - |S_i|) h. This counts overhangs of any angle; Lim & Soh do not state the overhang angle their support
// allowed.
double SupportVolume(const std::vector<std::vector<PolygonWithHoles>>& kept, double h) {
  double support_mm3 = 0.0;
  std::vector<PolygonWithHoles> shadow;
  for (int i = static_cast<int>(kept.size()) - 1; i >= 0; --i) {
    std::vector<PolygonWithHoles> both = shadow;
    both.insert(both.end(), kept[i].begin(), kept[i].end());
    shadow = internal::Union(both);
    support_mm3 += (Area(shadow) - Area(kept[i])) * h;
  }
  return support_mm3;
}

// The path points of `moves` (in S at height `top`, mm) into `layer` (part frame), each a copy of `bead` (tool
// direction, bead size, speed) at its place; sets the layer's mean z. False when the moves give no point.
bool FillLayerPoints(const std::vector<Move2D>& moves, const Eigen::Matrix3d& R_PS, double top, const PathPoint& bead,
                     LayerPath* layer) {
  for (const Move2D& move : moves) {
    PathPoint point = bead;
    point.p_P = R_PS * Eigen::Vector3d(move.p.x(), move.p.y(), top);
    point.weld = move.weld;
    layer->points.push_back(point);
  }
  if (layer->points.empty()) return false;
  double z_sum = 0.0;
  for (const PathPoint& p : layer->points) z_sum += p.p_P.z();
  layer->z_mm = z_sum / static_cast<double>(layer->points.size());
  return true;
}

// The sub-volumes: the user's split planes, or those of the centroid-shift decomposition (003 sec. 5.4), whose
// features' largest lean (deg) goes into `lean_deg` by sub-volume name.
std::vector<SubVolumeSpec> SubVolumeSpecs(const PlannerSections& scenario, const TriangleMesh& mesh,
                                          const std::string& where, std::map<std::string, double>* lean_deg) {
  if (scenario.slicing.split != SplitMethod::kCentroidShift) return scenario.slicing.sub_volumes;
  CentroidSplitOptions split;
  split.step_mm = scenario.slicing.layer_height_mm;
  split.overhang_deg = scenario.slicing.overhang_deg;
  const CentroidDecomposition decomposition = DecomposeByCentroidShift(mesh, split, where);
  for (const OverhangFeature& f : decomposition.features) (*lean_deg)[f.name] = f.max_gamma_deg;
  return decomposition.sub_volumes;
}

// The moves and pattern notes of each non-empty layer of a sub-volume, planned in parallel (each into its own slot);
// the layers are numbered in the plan from `first_index` on.
void PlanSubVolumeMoves(const std::vector<std::vector<PolygonWithHoles>>& kept, const PatternOptions& options,
                        int first_index, std::vector<std::vector<Move2D>>* layer_moves,
                        std::vector<std::vector<std::string>>* layer_notes) {
  const int count = static_cast<int>(kept.size());
  std::vector<int> plan_index(count, -1);
  for (int i = 0, next = first_index; i < count; ++i) {
    if (!kept[i].empty()) plan_index[i] = next++;
  }
  layer_moves->assign(count, {});
  layer_notes->assign(count, {});
  ParallelFor(count, [&](std::size_t i) {
    CheckInterrupt();
    if (kept[i].empty()) return;
    PatternOptions layer_options = options;
    layer_options.layer_index = plan_index[i];
    (*layer_moves)[i] = PlanLayerPattern(kept[i], layer_options, &(*layer_notes)[i]);
  });
}

// Plans sub-volume `spec` at about `d` mm per layer (its layers appended to `result`'s plan, their notes to its
// warnings; its layer thickness times its layers added to `height_sum`, mm) and returns its report. Throws InputError
// (`where` names the scenario) when it holds no metal along its direction.
SubVolumeReport PlanSubVolume(const TriangleMesh& mesh, const SubVolumeSpec& spec, const PatternOptions& options,
                              double d, const std::string& where, PlanResult* result, double* height_sum) {
  const Eigen::Vector3d n(spec.direction[0], spec.direction[1], spec.direction[2]);
  const SubVolumeSlices sliced = SliceSubVolume(mesh, spec, n, d, where);
  const std::vector<std::vector<PolygonWithHoles>>& kept = sliced.kept;
  const int count = static_cast<int>(kept.size());
  const double h = sliced.h;

  SubVolumeReport report;
  report.name = spec.name;
  report.direction = n;
  report.first_layer = static_cast<int>(result->plan.layers.size());
  report.keep = spec.keep;
  for (int i = 0; i < count; ++i) report.volume_mm3 += Area(kept[i]) * h;
  report.support_mm3 = SupportVolume(kept, h);
  std::vector<std::vector<Move2D>> layer_moves;
  std::vector<std::vector<std::string>> layer_notes;
  PlanSubVolumeMoves(kept, options, report.first_layer, &layer_moves, &layer_notes);
  PathPoint bead;
  bead.tool_dir_P = n;
  bead.bead_width_mm = result->bead_width_mm;
  bead.bead_height_mm = result->bead_height_mm;
  bead.speed_mm_s = result->travel_speed_mm_min / 60.0;
  for (int i = 0; i < count; ++i) {
    if (kept[i].empty()) continue;
    LayerPath layer;
    layer.index = static_cast<int>(result->plan.layers.size());
    layer.slice = kept[i];
    layer.slice_axes_P = sliced.R_PS.leftCols<2>();
    layer.build_dir_P = n;
    for (const std::string& note : layer_notes[i]) {
      result->warnings.push_back("layer " + std::to_string(layer.index) + ": " + note);
    }
    if (!FillLayerPoints(layer_moves[i], sliced.R_PS, sliced.lo + (i + 1) * h, bead, &layer)) {
      report.unwelded_mm3 += Area(kept[i]) * h;  // the pattern found no path in this slice
      continue;
    }
    result->plan.layers.push_back(std::move(layer));
    ++report.layers;
  }
  *height_sum += h * report.layers;
  return report;
}

}  // namespace

PlanResult PlanMultiDirectionalScenario(const PlannerSections& scenario, Progress* progress) {
  const std::string where = scenario.file.filename().string() + ": slicing";
  const ProcessSettings& process = scenario.process;
  WAAM_THROW_UNLESS(process.bead_model == BeadModel::kVolumeBalance,
                    scenario.file.filename().string() << ": process.bead_model = " << NameOf(process.bead_model)
                                                      << ": multi_directional plans with volume_balance only");
  PlanResult result;
  result.mesh = PartMesh(scenario.part, kWeldToleranceMm, &result.mesh_report);
  std::map<std::string, double> lean_deg;
  const std::vector<SubVolumeSpec> specs = SubVolumeSpecs(scenario, result.mesh, where, &lean_deg);
  SetVolumeBalanceBead(scenario, &result);
  const PatternOptions options = PatternOptionsFor(scenario, result.bead_width_mm);
  result.contour_tolerance_mm = options.contour_tolerance_mm;
  if (progress) progress->SetTotal(static_cast<int>(specs.size()));

  result.plan.name = scenario.name;
  double height_sum = 0.0;
  int sub_index = 0;
  for (const SubVolumeSpec& spec : specs) {
    SubVolumeReport report =
        PlanSubVolume(result.mesh, spec, options, scenario.slicing.layer_height_mm, where, &result, &height_sum);
    if (lean_deg.count(spec.name)) report.centroid_lean_deg = lean_deg.at(spec.name);
    result.sub_volumes.push_back(report);
    if (progress) progress->Update(++sub_index);
  }
  if (progress) progress->Finish();
  WAAM_THROW_UNLESS(!result.plan.layers.empty(), where << ": no sub-volume gave a layer to weld");
  result.layer_height_mm = height_sum / static_cast<double>(result.plan.layers.size());
  result.stats = ComputeStats(result.plan);
  return result;
}

}  // namespace waam::planner
