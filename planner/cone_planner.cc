// Cone and cylinder planning of Dai et al. 2020 sec. 2 and 4-5: slice with equidistant surfaces, flatten, fill with
// the planar patterns, map back, tool along the normal, CSW speed from the curvature of the flat path.
#include "planner/cone_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "models/bead/csw_model.h"
#include "models/bead/parabolic_bead.h"
#include "models/core/error.h"
#include "models/core/numbers.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "planner/geometry/clipper_adapter.h"
#include "planner/geometry/polygon.h"
#include "planner/mesh/generators.h"
#include "planner/mesh/mesh_ops.h"
#include "planner/plan_scenario.h"
#include "planner/path/layer_pattern.h"
#include "planner/slicing/cone_slicer.h"

namespace waam::planner {
namespace {

constexpr double kWeldToleranceMm = 1e-4;
constexpr double kInf = std::numeric_limits<double>::infinity();
// Longest step between path points after mapping back: a straight flat line is a geodesic, curved in space.
constexpr double kPointStepMm = 2.0;

// Circumradius of three flat points (mm); +inf when they are collinear.
double CircumRadius(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double cross = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  if (std::abs(cross) < 1e-9) return kInf;
  return (b - a).norm() * (c - b).norm() * (c - a).norm() / (2.0 * std::abs(cross));
}

// Curvature radius (mm) of each point of a flat weld pass, from the points about `window_mm` of arc before and after
// it. The flattening is an isometry, so this is the geodesic curvature radius of the bead on the surface, the radius
// the CSW model was fitted for (beads on a flat plate, Dai sec. 4).
std::vector<double> PassRadii(const std::vector<Eigen::Vector2d>& pass, double window_mm) {
  const std::size_t n = pass.size();
  std::vector<double> s(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) s[i] = s[i - 1] + (pass[i] - pass[i - 1]).norm();
  std::vector<double> radii(n, kInf);
  std::size_t lo = 0;
  std::size_t hi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    while (lo + 1 < i && s[i] - s[lo + 1] >= window_mm) ++lo;
    hi = std::max(hi, i);
    while (hi + 1 < n && s[hi] - s[i] < window_mm) ++hi;
    if (lo < i && hi > i) radii[i] = CircumRadius(pass[lo], pass[i], pass[hi]);
  }
  return radii;
}

// The bead of a cone layer: width from the scenario; speed from the CSW model per point (the straight-line speed is
// the nominal one), or the scenario's speed; height from the wire-feed volume balance (003 eq. 3.4, 3.3).
class ConeBead {
 public:
  explicit ConeBead(const PlannerSections& scenario)
      : process_(scenario.process),
        width_(scenario.path.bead_width_mm),
        csw_(scenario.process.bead_model == BeadModel::kCsw ? scenario.process.csw.get() : nullptr) {
    WAAM_DEMAND(process_.bead_model != BeadModel::kCsw || csw_ != nullptr);
  }
  // Travel speed (mm/min) for a bead of the scenario's width along a path of curvature radius `radius_mm`; `clamp`
  // (may be null) says whether the CSW model clamped it.
  double Speed(double radius_mm, models::SpeedClamp* clamp) const {
    if (csw_ == nullptr) return process_.travel_speed_mm_min;
    const models::SpeedChoice choice = csw_->SpeedForWidth(width_, radius_mm);
    if (clamp) *clamp = choice.clamp;
    return choice.speed_mm_per_min;
  }
  // Bead section area (mm^2) at travel speed `speed_mm_min`, from the wire feed.
  double Area(double speed_mm_min) const {
    return models::BeadAreaFromWireFeed(process_.wire_diameter_mm, process_.wire_feed_mm_min, speed_mm_min,
                                        process_.deposition_efficiency);
  }
  // Speed, bead width and height of `point`, on a flat path of curvature radius `radius_mm`. The model is used only
  // where it describes the bead: corners count as straight and tight curves as the smallest radius of its data
  // (CswModel::ApplicableRadius, the twin's rule too).
  void Fill(double radius_mm, PathPoint* point) const {
    const double r = models::CswModel::ApplicableRadius(radius_mm, width_, process_.csw_min_radius_mm);
    const double speed = Speed(r, nullptr);
    point->speed_mm_s = speed / 60.0;
    point->bead_width_mm = csw_ != nullptr ? csw_->Width(speed, r) : width_;
    point->bead_height_mm = 1.5 * Area(speed) / point->bead_width_mm;
  }

 private:
  const ProcessSettings& process_;
  double width_;
  const models::CswModel* csw_;
};

// The number of cone (or cylinder) layers of height `d` (mm) that cover `mesh`, growing away from the axis. Throws
// InputError (`where` names the scenario) when the part reaches past the cone's apex or lies inside the first surface.
int ConeLayerCount(const TriangleMesh& mesh, const ConeSurface& base, double d, const std::string& where) {
  // The layers grow away from the axis; the part must lie on the nappe's side of the apex and outside the surface.
  double max_offset = -kInf;
  for (const Eigen::Vector3d& v : mesh.vertices) {
    if (!base.cylinder()) {
      const double z = v.z() - base.axis_P.z();
      WAAM_THROW_UNLESS(z / base.H < 1.0, where << ": the part reaches past the cone apex (vertex at z = " << v.z()
                                                << " mm, apex at z = " << base.axis_P.z() + base.H
                                                << " mm); the cone slices only the nappe below its apex");
    }
    max_offset = std::max(max_offset, base.NormalOffset(v));
  }
  WAAM_THROW_UNLESS(max_offset > 0.5 * d, where << ": the part lies inside the first surface (largest normal "
                                                << "distance " << max_offset << " mm, layer height " << d
                                                << " mm); the layers grow away from the axis");
  return std::max(1, static_cast<int>(std::ceil(max_offset / d - 0.5)));
}

// Densifies every move on the development plane, so that the mapped path follows the surface: points `q_flat` at
// most kPointStepMm apart, and per point whether the move to it welds. A weld move stays inside its region; a travel
// move between regions of a cone is interpolated in the polar coordinates of the development, because a straight
// line between two points of a sector wider than pi can leave the sector (and cross the cutting line).
void DensifyMoves(const std::vector<Move2D>& moves, const ConeSurface& middle, std::vector<Eigen::Vector2d>* q_flat,
                  std::vector<bool>* weld) {
  for (const Move2D& move : moves) {
    if (!q_flat->empty()) {
      const Eigen::Vector2d from = q_flat->back();
      const bool polar = !move.weld && !middle.cylinder();
      const double rho0 = from.norm(), rho1 = move.p.norm();
      const double phi0 = std::atan2(from.y(), from.x()), phi1 = std::atan2(move.p.y(), move.p.x());
      const double length = polar ? std::max(std::abs(rho1 - rho0), std::max(rho0, rho1) * std::abs(phi1 - phi0))
                                  : (move.p - from).norm();
      const int steps = std::max(1, static_cast<int>(std::ceil(length / kPointStepMm)));
      for (int k = 1; k < steps; ++k) {
        const double f = static_cast<double>(k) / steps;
        const double rho = rho0 + f * (rho1 - rho0), phi = phi0 + f * (phi1 - phi0);
        q_flat->push_back(polar ? Eigen::Vector2d(rho * std::cos(phi), rho * std::sin(phi)) : from + (move.p - from) * f);
        weld->push_back(move.weld);
      }
    }
    q_flat->push_back(move.p);
    weld->push_back(q_flat->size() == 1 ? false : move.weld);
  }
}

// Curvature radius (mm) per point along each weld pass of a densified flat path (a pass starts at the point before
// its first weld move); +inf off the passes.
std::vector<double> PathRadii(const std::vector<Eigen::Vector2d>& q_flat, const std::vector<bool>& weld,
                              double window_mm) {
  std::vector<double> radius(q_flat.size(), kInf);
  for (std::size_t j = 1; j < q_flat.size();) {
    if (!weld[j]) {
      ++j;
      continue;
    }
    std::size_t end = j;
    while (end < q_flat.size() && weld[end]) ++end;
    const std::vector<Eigen::Vector2d> pass(q_flat.begin() + (j - 1), q_flat.begin() + end);
    const std::vector<double> r = PassRadii(pass, window_mm);
    for (std::size_t k = 0; k < r.size(); ++k) radius[j - 1 + k] = r[k];
    j = end;
  }
  return radius;
}

// Appends a planned layer to `result` with the next index and its pattern notes as warnings; a layer whose pattern
// found no room for a bead is left out (its notes still count), so the plan numbers the others in order.
void AppendLayer(LayerPath layer, const std::vector<std::string>& notes, PlanResult* result) {
  const int index = static_cast<int>(result->plan.layers.size());
  for (const std::string& note : notes) result->warnings.push_back("layer " + std::to_string(index) + ": " + note);
  if (layer.points.empty()) return;
  layer.index = index;
  result->plan.layers.push_back(std::move(layer));
}

// Sets `result`'s bead of cone layers `d` mm high: the scenario's width, the straight-line speed of `bead` (with
// the CSW model's clamp), the area from the wire feed at that speed and the layer growth at the zigzag spacing.
void SetConeBead(const PlannerSections& scenario, const ConeBead& bead, double d, PlanResult* result) {
  const double width = scenario.path.bead_width_mm;
  models::SpeedClamp straight_clamp = models::SpeedClamp::kNone;
  result->layer_height_mm = d;
  result->bead_width_mm = width;
  result->travel_speed_mm_min = bead.Speed(kInf, &straight_clamp);
  result->speed_clamp = models::ToString(straight_clamp);
  result->bead_area_mm2 = bead.Area(result->travel_speed_mm_min);
  result->bead_height_mm = 1.5 * result->bead_area_mm2 / width;
  result->layer_growth_mm = result->bead_area_mm2 / OverlapSpacingFor(scenario.path.overlap_model, width).zigzag_mm;
}

// Each of the `layer_count` layers sliced at its middle surface (offset (i + 0.5) d from `base`) and flattened onto
// the development plane, in parallel; nothing where the surface misses the part.
std::vector<std::optional<FlatLayer>> FlattenLayers(const TriangleMesh& mesh, const ConeSurface& base, double d,
                                                    double step_rad, int layer_count) {
  std::vector<std::optional<FlatLayer>> flats(layer_count);
  ParallelFor(layer_count, [&](std::size_t i) {
    CheckInterrupt();
    // Slice at the layer's middle, weld on its top: both are equidistant surfaces of the first one (sec. 5).
    const ConeSurface middle = base.Offset((i + 0.5) * d);
    const std::vector<Contour3d> contours = SliceWithCone(mesh, middle, nullptr);
    if (!contours.empty()) flats[i] = FlattenLayer(contours, middle, step_rad);
  });
  return flats;
}

// The path points of flat moves mapped back onto the top surface of the layer whose middle surface is `middle`
// (`d` mm thick), the tool along the surface normal, each bead from the flat path's curvature radius over
// `window_mm`; sets the layer's mean build direction and z.
void MapBackToSurface(const std::vector<Move2D>& moves, const ConeSurface& middle, double alpha, double d,
                      const ConeBead& bead, double window_mm, LayerPath* layer) {
  std::vector<Eigen::Vector2d> q_flat;
  std::vector<bool> weld;
  DensifyMoves(moves, middle, &q_flat, &weld);
  const std::vector<double> radius = PathRadii(q_flat, weld, window_mm);
  Eigen::Vector3d dir_sum = Eigen::Vector3d::Zero();
  double z_sum = 0.0;
  for (std::size_t j = 0; j < q_flat.size(); ++j) {
    const Eigen::Vector3d p_middle = middle.Unflatten(q_flat[j], alpha);
    const Eigen::Vector3d n = middle.Normal(p_middle);
    PathPoint point;
    point.p_P = p_middle + 0.5 * d * n;  // on the top surface, offset (i + 1) d
    point.tool_dir_P = n;
    point.weld = weld[j];
    bead.Fill(radius[j], &point);
    dir_sum += n;
    z_sum += point.p_P.z();
    layer->points.push_back(point);
  }
  if (!layer->points.empty()) {
    layer->build_dir_P = dir_sum.normalized();
    layer->z_mm = z_sum / static_cast<double>(layer->points.size());
  }
}

// What every cone layer is planned with: the scenario, the first surface, the layer height d (mm), the bead, the
// pattern options and the curvature window (mm).
struct ConeLayerContext {
  const PlannerSections& scenario;
  const std::string& where;
  const ConeSurface& base;
  double d;
  const ConeBead& bead;
  const PatternOptions& options;
  double window_mm;
};

// Plans cone layer `i` (numbered `plan_index` in the plan) from its flattened slice: the pattern on the development
// plane, mapped back. Throws InputError when the flattening failed or the pattern found no weld path where a bead
// fits.
LayerPath PlanConeLayer(const ConeLayerContext& c, int i, const FlatLayer& flat, int plan_index,
                        std::vector<std::string>* notes) {
  const ConeSurface middle = c.base.Offset((i + 0.5) * c.d);
  WAAM_THROW_UNLESS(flat.ok, c.where << ": layer " << i << " (surface R = " << middle.R << " mm): " << flat.message);
  LayerPath layer;
  layer.index = plan_index;
  layer.slice = flat.regions;
  layer.slice_in_plane = false;  // the development plane
  PatternOptions layer_options = c.options;
  layer_options.layer_index = layer.index;
  const std::vector<Move2D> moves = PlanLayerPattern(flat.regions, layer_options, notes);
  WAAM_THROW_UNLESS(HasWeldOrNoRoom(flat.regions, moves, c.scenario.path.bead_width_mm),
                    c.where << ": layer " << i << " (surface R = " << middle.R << " mm): path.pattern '"
                            << NameOf(c.scenario.path.pattern) << "' found no weld path in the flattened slice of "
                            << Area(flat.regions) << " mm^2; try path.pattern: contour");
  MapBackToSurface(moves, middle, flat.alpha, c.d, c.bead, c.window_mm, &layer);
  return layer;
}

}  // namespace

PlanResult PlanConeScenario(const PlannerSections& scenario, Progress* progress) {
  const SlicingSettings& slicing = scenario.slicing;
  const std::string where = scenario.file.filename().string() + ": slicing";
  PlanResult result;
  result.mesh = PartMesh(scenario.part, kWeldToleranceMm, &result.mesh_report);

  ConeSurface base;
  base.axis_P = Eigen::Vector3d(slicing.cone_axis_mm[0], slicing.cone_axis_mm[1], slicing.cone_axis_mm[2]);
  base.R = slicing.cone_R_mm;
  base.H = slicing.type == SlicingType::kCylinder ? kInf : slicing.cone_H_mm;
  const double d = slicing.layer_height_mm;
  const int layer_count = ConeLayerCount(result.mesh, base, d, where);
  if (progress) progress->SetTotal(layer_count);

  const ConeBead bead(scenario);
  SetConeBead(scenario, bead, d, &result);
  const PatternOptions options = PatternOptionsFor(scenario, result.bead_width_mm);
  result.contour_tolerance_mm = options.contour_tolerance_mm;
  const double step_rad = slicing.cone_rotation_step_deg * kPi / 180.0;
  const double window_mm = std::max(0.5 * result.bead_width_mm, 2.0 * kPointStepMm);
  const ConeLayerContext context{scenario, where, base, d, bead, options, window_mm};

  result.plan.name = scenario.name;
  // The layers are independent once each knows its index in the plan (the count of non-empty layers below it, which
  // seeds its start point): slice and flatten every surface in parallel, number the layers, then plan and map them
  // back in parallel, each into its own slot. An error is thrown for the lowest layer that has one, as a serial loop
  // would, so the plan and its errors are the same on any number of threads.
  const std::vector<std::optional<FlatLayer>> flats = FlattenLayers(result.mesh, base, d, step_rad, layer_count);
  std::vector<int> plan_index(layer_count, -1);
  int planned = 0;
  for (int i = 0; i < layer_count; ++i) {
    if (flats[i]) plan_index[i] = planned++;
  }
  std::vector<LayerPath> layers(layer_count);
  std::vector<std::vector<std::string>> layer_notes(layer_count);
  std::mutex progress_mutex;
  int layers_done = 0;
  ParallelFor(layer_count, [&](std::size_t i) {
    CheckInterrupt();
    if (!flats[i]) return;
    layers[i] = PlanConeLayer(context, static_cast<int>(i), *flats[i], plan_index[i], &layer_notes[i]);
    if (progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress->Update(++layers_done);
    }
  });
  for (int i = 0; i < layer_count; ++i) {
    if (flats[i]) AppendLayer(std::move(layers[i]), layer_notes[i], &result);
  }
  if (progress) progress->Finish();
  WAAM_THROW_UNLESS(!result.plan.layers.empty(), where << ": no layer of the part meets the surfaces");
  result.stats = ComputeStats(result.plan);
  return result;
}

}  // namespace waam::planner
