// Bent-tube planning: skeleton slicing (sec. 6.3.1), per-point speed and width from the bead models (sec. 6.3.2.1,
// eq. 6.6-6.7), inner/outer walls (Fig. 64), the eq. 6.4 design rule, and the spiral or per-layer path (Fig. 76).
#include "planner/skeleton_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "models/bead/parabolic_bead.h"
#include "models/core/error.h"
#include "models/core/numbers.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "planner/mesh/generators.h"
#include "planner/mesh/mesh_ops.h"
#include "planner/plan_scenario.h"
#include "planner/mesh/tube_generators.h"

namespace waam::planner {
namespace {

constexpr double kWeldToleranceMm = 1e-4;

// A layer's closed mid curve in the part frame, parametrised by arc-length fraction f in [0, 1] from a start point.
class ClosedCurve {
 public:
  ClosedCurve(const SkeletonLayer& layer, const Eigen::Vector3d* start_near) {
    std::vector<Eigen::Vector3d> pts;
    for (const Eigen::Vector2d& q : layer.mid_curve) pts.push_back(layer.ToPart(q));
    std::size_t start = 0;
    if (start_near) {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const double d = (pts[i] - *start_near).squaredNorm();
        if (d < best) best = d, start = i;
      }
    }
    std::rotate(pts.begin(), pts.begin() + static_cast<long>(start), pts.end());
    pts.push_back(pts.front());
    pts_ = std::move(pts);
    cum_.assign(pts_.size(), 0.0);
    for (std::size_t i = 1; i < pts_.size(); ++i) cum_[i] = cum_[i - 1] + (pts_[i] - pts_[i - 1]).norm();
  }
  double length() const { return cum_.back(); }
  Eigen::Vector3d At(double f) const {
    const double s = std::clamp(f, 0.0, 1.0) * length();
    const auto it = std::upper_bound(cum_.begin(), cum_.end(), s);
    const std::size_t i = std::clamp<std::size_t>(static_cast<std::size_t>(it - cum_.begin()), 1, pts_.size() - 1);
    const double span = cum_[i] - cum_[i - 1];
    const double t = span > 0.0 ? (s - cum_[i - 1]) / span : 0.0;
    return pts_[i - 1] + t * (pts_[i] - pts_[i - 1]);
  }
  const Eigen::Vector3d& start() const { return pts_.front(); }

 private:
  std::vector<Eigen::Vector3d> pts_;
  std::vector<double> cum_;
};

// Inner and outer wall of a layer from its points and widths (Fig. 64): each point shifted by -+ w/2 in the plane,
// perpendicular to the curve; plane coordinates of `layer`.
PolygonWithHoles Walls(const SkeletonLayer& layer, const std::vector<Eigen::Vector3d>& p_P,
                       const std::vector<double>& width_mm) {
  const std::size_t n = p_P.size();
  std::vector<Eigen::Vector2d> q(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d d = p_P[i] - layer.origin_P;
    q[i] = Eigen::Vector2d(d.dot(layer.e1_P), d.dot(layer.e2_P));
  }
  PolygonWithHoles walls;
  Ring inner;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d tangent = (q[(i + 1) % n] - q[(i + n - 1) % n]).normalized();
    const Eigen::Vector2d outward(tangent.y(), -tangent.x());  // the curve runs counter-clockwise
    walls.outer.push_back(q[i] + 0.5 * width_mm[i] * outward);
    inner.push_back(q[i] - 0.5 * width_mm[i] * outward);
  }
  std::reverse(inner.begin(), inner.end());
  walls.holes.push_back(std::move(inner));
  return walls;
}

// The aligned curves C_-1 (base) ... C_(n-1) of a skeleton slicing and the bead models: builds each layer (or spiral
// loop) of the plan from them. The starts are aligned so that the seam runs straight up the part.
class SkeletonPathBuilder {
 public:
  SkeletonPathBuilder(const SkeletonSlicing& slicing, const models::SpeedHeightModel& speed_height,
                      const models::WidthHeightModel& width_height, double point_spacing_mm)
      : slicing_(slicing),
        speed_height_(speed_height),
        width_height_(width_height),
        spacing_mm_(point_spacing_mm),
        n_(static_cast<int>(slicing.layers.size())) {
    curves_.emplace_back(slicing.base, nullptr);
    for (int i = 0; i < n_; ++i) curves_.emplace_back(slicing.layers[i], &curves_.back().start());
  }

  // Layer i: one closed pass along C_i, each point's bead from the local layer thickness.
  LayerPath Contour(int i) const {
    const SkeletonLayer& layer = slicing_.layers[i];
    const ClosedCurve& curve = curves_[i + 1];
    const int count = std::max(3, static_cast<int>(std::lround(curve.length() / spacing_mm_)));
    LayerPath path = EmptyPath(i, layer);
    std::vector<Eigen::Vector3d> ring;
    std::vector<double> widths;
    for (int k = 0; k <= count; ++k) {
      const double f = static_cast<double>(k) / count;
      path.points.push_back(MakePoint(curve.At(f), layer.normal_P, Thickness(i, f), k > 0));
      if (k < count) ring.push_back(path.points.back().p_P), widths.push_back(path.points.back().bead_width_mm);
    }
    path.slice = {Walls(layer, ring, widths)};
    return path;
  }

  // Spiral loop j: blends C_(j-1) into C_j with thickness (1 - f) H_(j-1) + f H_j (H_-1 = H_n = 0, C_n = C_(n-1)),
  // so every loop lies one local layer thickness above the previous loop and the whole part is one pass.
  LayerPath SpiralLoop(int j) const {
    const int to = std::min(j, n_ - 1);
    const ClosedCurve& a = curves_[j];       // C_(j-1)
    const ClosedCurve& b = curves_[to + 1];  // C_j
    const SkeletonLayer& layer = slicing_.layers[to];
    const Eigen::Vector3d& n_a = LayerOf(j).normal_P;
    const int count = std::max(3, static_cast<int>(std::lround(b.length() / spacing_mm_)));
    LayerPath path = EmptyPath(j, layer);
    std::vector<Eigen::Vector3d> ring;
    std::vector<double> widths;
    for (int k = (j == 0 ? 0 : 1); k <= count; ++k) {
      const double f = static_cast<double>(k) / count;
      const Eigen::Vector3d p = j == n_ ? b.At(f) : Eigen::Vector3d((1.0 - f) * a.At(f) + f * b.At(f));
      const double h = (1.0 - f) * Thickness(j - 1, f) + f * Thickness(j, f);
      const Eigen::Vector3d dir = (1.0 - f) * n_a + f * layer.normal_P;
      path.points.push_back(MakePoint(p, dir, h, k > 0));
      ring.push_back(p);
      widths.push_back(path.points.back().bead_width_mm);
    }
    if (ring.size() > 3 && (ring.front() - ring.back()).norm() < 1e-9) ring.pop_back(), widths.pop_back();
    path.slice = {Walls(layer, ring, widths)};
    return path;
  }

 private:
  const SkeletonLayer& LayerOf(int c) const { return c == 0 ? slicing_.base : slicing_.layers[c - 1]; }

  // H_i(f): thickness of layer i at fraction f, the distance of C_i(f) to the plane below (mm).
  double Thickness(int i, double f) const {
    if (i < 0 || i >= n_) return 0.0;
    const SkeletonLayer& below = LayerOf(i);
    return (curves_[i + 1].At(f) - below.centroid_P).dot(below.normal_P);
  }

  // eq. 6.6 (speed for the thickness `h` mm, clamped to the feasible window) and eq. 6.7 (the width that comes with
  // it) at point `p` with the tool along `dir`.
  PathPoint MakePoint(const Eigen::Vector3d& p, const Eigen::Vector3d& dir, double h, bool weld) const {
    const models::BeadSetpoint set = models::SetpointForHeight(speed_height_, width_height_, std::max(h, 1e-3));
    PathPoint point;
    point.p_P = p;
    point.tool_dir_P = dir.normalized();
    point.bead_height_mm = set.speed.achieved_mm;
    point.bead_width_mm = set.width_mm;
    point.speed_mm_s = set.speed.speed_mm_per_min / 60.0;
    point.weld = weld;
    return point;
  }

  // A path numbered `index` in the plane of `layer`, without points.
  static LayerPath EmptyPath(int index, const SkeletonLayer& layer) {
    LayerPath path;
    path.index = index;
    path.z_mm = layer.centroid_P.z();
    path.build_dir_P = layer.normal_P;
    path.slice_axes_P << layer.e1_P, layer.e2_P;
    path.slice_origin_P = layer.origin_P;
    return path;
  }

  const SkeletonSlicing& slicing_;
  const models::SpeedHeightModel& speed_height_;
  const models::WidthHeightModel& width_height_;
  double spacing_mm_;
  int n_;
  std::vector<ClosedCurve> curves_;
};

}  // namespace

void CheckBendRule(double bend_radius_mm, double extent_mm, double h_min_mm, double h_max_mm,
                   const std::string& where) {
  const double r_min = MinimumBendRadius(extent_mm, h_min_mm, h_max_mm);
  WAAM_THROW_UNLESS(bend_radius_mm >= r_min * (1.0 - 1e-6),
                    where << ": bend radius " << bend_radius_mm << " mm is tighter than R_min = " << r_min
                          << " mm for a section of d = " << extent_mm << " mm with layers of " << h_min_mm << "-"
                          << h_max_mm << " mm (eq. 6.4: R_min = d/2 (lambda + 1)/(lambda - 1), lambda = h_max/h_min = "
                          << h_max_mm / h_min_mm << "; 1.5 d for 1-2 mm): the inner wall would need layers thinner "
                             "than h_min where the outer wall needs h_max");
}

Plan BuildSkeletonPlan(const SkeletonSlicing& slicing, const models::SpeedHeightModel& speed_height,
                       const models::WidthHeightModel& width_height, const SkeletonPathOptions& options,
                       const std::string& name) {
  WAAM_THROW_UNLESS(options.point_spacing_mm > 0.0,
                    "slicing.point_spacing_mm = " << options.point_spacing_mm << ": must be > 0");
  const int n = static_cast<int>(slicing.layers.size());
  const SkeletonPathBuilder builder(slicing, speed_height, width_height, options.point_spacing_mm);
  // Once the curves are aligned (in order, by the builder), every layer or loop depends only on its curves: they are
  // built in parallel, each into its own slot.
  Plan plan;
  plan.name = name;
  const int paths = options.spiral ? n + 1 : n;
  plan.layers.resize(paths);
  ParallelFor(paths, [&](std::size_t i) {
    plan.layers[i] = options.spiral ? builder.SpiralLoop(static_cast<int>(i)) : builder.Contour(static_cast<int>(i));
  });
  return plan;
}

namespace {

// eq. 6.4 on a bent-tube generator's own numbers, before any slicing. Throws InputError where the bend is too tight.
void CheckGeneratorBend(const PlannerSections& scenario) {
  const SlicingSettings& s = scenario.slicing;
  const BentTubeSpec spec = BentTubeSpecFromParams(
      ResolveGeneratorParams(PartGenerator::kBentTube, scenario.part.params, scenario.part.where));
  const TubePart tube = BuildBentTube(spec, scenario.part.where);
  CheckBendRule(spec.bend_radius_mm, tube.extent_in_bend_plane_mm, s.h_min_mm, s.h_max_mm,
                scenario.part.where + " bent_tube.bend_radius_mm");
}

// eq. 6.4 on a mesh: the tightest bend measured along the centroid chain of `slicing` (+-3 layers), 2 % slack for
// facets. Throws InputError where the bend is too tight.
void CheckMeshBend(const PlannerSections& scenario, const SkeletonSlicing& slicing) {
  const SlicingSettings& s = scenario.slicing;
  const BendEstimate bend = EstimateTightestBend(slicing, 3);
  if (std::isfinite(bend.radius_mm) &&
      1.02 * bend.radius_mm < MinimumBendRadius(bend.extent_mm, s.h_min_mm, s.h_max_mm)) {
    std::ostringstream where;
    where << scenario.part.where << " (bend measured along the centroid chain at layer " << bend.layer << ")";
    CheckBendRule(bend.radius_mm, bend.extent_mm, s.h_min_mm, s.h_max_mm, where.str());
  }
}

// The summary fields of a skeleton plan: means and ranges over the weld points (the planar fields hold one value for
// all points), and the most frequent speed clamp among the clamped points, or none.
void SummariseBeads(const models::SpeedHeightModel& speed_height, PlanResult* result) {
  double sum_h = 0.0, sum_w = 0.0, sum_v = 0.0, sum_area = 0.0;
  std::size_t count = 0;
  result->layer_height_min_mm = result->speed_min_mm_min = std::numeric_limits<double>::infinity();
  std::map<models::SpeedClamp, std::size_t> clamps;
  for (const LayerPath& layer : result->plan.layers) {
    for (const PathPoint& p : layer.points) {
      if (!p.weld) continue;
      ++count;
      sum_h += p.bead_height_mm;
      sum_w += p.bead_width_mm;
      sum_v += p.speed_mm_s * 60.0;
      sum_area += models::ParabolicBead{p.bead_width_mm, p.bead_height_mm}.Area();
      result->layer_height_min_mm = std::min(result->layer_height_min_mm, p.bead_height_mm);
      result->layer_height_max_mm = std::max(result->layer_height_max_mm, p.bead_height_mm);
      result->speed_min_mm_min = std::min(result->speed_min_mm_min, p.speed_mm_s * 60.0);
      result->speed_max_mm_min = std::max(result->speed_max_mm_min, p.speed_mm_s * 60.0);
      const double v = p.speed_mm_s * 60.0;
      ++clamps[v <= speed_height.feasible().min_mm_per_min * (1 + 1e-9)   ? models::SpeedClamp::kAtMinimum
               : v >= speed_height.feasible().max_mm_per_min * (1 - 1e-9) ? models::SpeedClamp::kAtMaximum
                                                                           : models::SpeedClamp::kNone];
    }
  }
  const double k = count ? 1.0 / count : 0.0;
  result->layer_height_mm = sum_h * k;
  result->bead_height_mm = sum_h * k;
  result->bead_width_mm = sum_w * k;
  result->travel_speed_mm_min = sum_v * k;
  result->bead_area_mm2 = sum_area * k;
  result->layer_growth_mm = sum_h * k;  // a single bead per layer grows the wall by its own height
  std::size_t most = 0;
  for (const auto& [clamp, points] : clamps) {
    if (clamp != models::SpeedClamp::kNone && points > most) most = points, result->speed_clamp = models::ToString(clamp);
  }
}

}  // namespace

PlanResult PlanSkeletonScenario(const PlannerSections& scenario, Progress* progress) {
  const SlicingSettings& s = scenario.slicing;
  PlanResult result;
  if (scenario.part.mesh_path.empty() && scenario.part.generator == PartGenerator::kBentTube) {
    CheckGeneratorBend(scenario);
  }
  result.mesh = PartMesh(scenario.part, kWeldToleranceMm, &result.mesh_report);
  const double shift = PlaceOnBuildPlate(&result.mesh);
  result.mesh_report.bbox_min.z() += shift;
  result.mesh_report.bbox_max.z() += shift;

  SkeletonSliceOptions slice_options;
  slice_options.h_min_mm = s.h_min_mm;
  slice_options.h_max_mm = s.h_max_mm;
  slice_options.first_step_mm = s.first_step_mm;
  slice_options.beta_rad = s.beta_deg * kPi / 180.0;
  slice_options.wall_mm = s.wall_mm;
  const SkeletonSlicing slicing = SliceAlongSkeleton(result.mesh, slice_options, progress);
  WAAM_THROW_UNLESS(!slicing.layers.empty(), scenario.part.where << ": skeleton slicing found no layer above the "
                                                                    "base; is the part thicker than h_min_mm?");
  if (scenario.part.generator != PartGenerator::kBentTube) CheckMeshBend(scenario, slicing);

  WAAM_DEMAND(scenario.process.speed_height != nullptr && scenario.process.width_height != nullptr);
  SkeletonPathOptions path_options;
  path_options.point_spacing_mm = s.point_spacing_mm;
  path_options.spiral = scenario.path.pattern == Pattern::kSpiral;
  result.plan = BuildSkeletonPlan(slicing, *scenario.process.speed_height, *scenario.process.width_height,
                                  path_options, scenario.name);
  result.stats = ComputeStats(result.plan);
  result.axis_P = CentroidChain(slicing);
  result.layers_out_of_range = slicing.out_of_range_layers;
  SummariseBeads(*scenario.process.speed_height, &result);
  return result;
}

}  // namespace waam::planner
