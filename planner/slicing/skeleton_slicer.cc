// Adaptive skeleton slicing: each plane is placed at G = I_i + h' N (sec. 6.3.1), re-oriented perpendicular to
// V = I_(i+1) - I_i until gamma <= beta (eq. 5.23-5.26), and h' rescaled by Fig. 56 until the layer thickness over the
// section lies within [h_min, h_max].
#include "planner/slicing/skeleton_slicer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Geometry>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "models/core/progress.h"
#include "planner/geometry/clipper_adapter.h"
#include "planner/slicing/planar_slicer.h"

namespace waam::planner {
namespace {

// Area centroid of a region (outer counter-clockwise, holes clockwise), plane coordinates.
Eigen::Vector2d Centroid(const PolygonWithHoles& region) {
  double a2 = 0.0;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  auto add = [&](const Ring& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Eigen::Vector2d& p = ring[i];
      const Eigen::Vector2d& q = ring[(i + 1) % ring.size()];
      const double cross = p.x() * q.y() - q.x() * p.y();
      a2 += cross;
      c += (p + q) * cross;
    }
  };
  add(region.outer);
  for (const Ring& hole : region.holes) add(hole);
  return std::abs(a2) > 1e-12 ? Eigen::Vector2d(c / (3.0 * a2)) : region.outer.front();
}

// A candidate plane and its cut.
struct Cut {
  SkeletonLayer layer;
  bool found = false;
};

// Cuts the mesh with the plane through `origin` with unit `normal`; e1 is `e1_hint` made orthogonal to the normal.
// Keeps the region whose centroid is nearest the origin, if it lies within `reach_mm` of it and looks like the
// section below (`like`: same number of holes, area within 25 %; null = any). A cut that also runs through an end
// face (past the top of the part) is not like its predecessor and counts as no cut.
Cut CutPlane(const TriangleMesh& mesh, const Eigen::Vector3d& origin, const Eigen::Vector3d& normal,
             const Eigen::Vector3d& e1_hint, double reach_mm, const PolygonWithHoles* like = nullptr) {
  Cut cut;
  SkeletonLayer& layer = cut.layer;
  layer.origin_P = origin;
  layer.normal_P = normal.normalized();
  Eigen::Vector3d e1 = e1_hint - e1_hint.dot(layer.normal_P) * layer.normal_P;
  if (e1.norm() < 1e-9) e1 = layer.normal_P.unitOrthogonal();
  layer.e1_P = e1.normalized();
  layer.e2_P = layer.normal_P.cross(layer.e1_P);
  // Into plane coordinates (rows e1, e2, n), then the planar slicer cuts at z = 0.
  Eigen::Matrix3d R;
  R.row(0) = layer.e1_P.transpose();
  R.row(1) = layer.e2_P.transpose();
  R.row(2) = layer.normal_P.transpose();
  // Only the facets that cross the plane near the origin go to the slicer (2 x reach: the whole section fits; a
  // ring of another branch of the part cut by that sphere is an open chain and is left out).
  const double radius2 = std::isfinite(reach_mm) ? 4.0 * reach_mm * reach_mm : std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector3d> moved(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) moved[i] = R * (mesh.vertices[i] - origin);
  std::vector<int> remap(mesh.vertices.size(), -1);
  TriangleMesh local;
  for (const std::array<int, 3>& f : mesh.facets) {
    const double lo = std::min({moved[f[0]].z(), moved[f[1]].z(), moved[f[2]].z()});
    const double hi = std::max({moved[f[0]].z(), moved[f[1]].z(), moved[f[2]].z()});
    if (lo > 0.0 || hi < 0.0) continue;
    if (moved[f[0]].squaredNorm() > radius2 && moved[f[1]].squaredNorm() > radius2 &&
        moved[f[2]].squaredNorm() > radius2) {
      continue;
    }
    std::array<int, 3> g;
    for (int k = 0; k < 3; ++k) {
      if (remap[f[k]] < 0) {
        remap[f[k]] = static_cast<int>(local.vertices.size());
        local.vertices.push_back(moved[f[k]]);
      }
      g[k] = remap[f[k]];
    }
    local.facets.push_back(g);
  }
  SliceReport report;
  if (local.facets.empty()) return cut;
  const std::vector<PolygonWithHoles> regions = SlicePlanar(local, {0.0}, &report).front();
  double best = reach_mm;
  const double like_area = like ? Area(*like) : 0.0;
  for (const PolygonWithHoles& region : regions) {
    if (like && (region.holes.size() != like->holes.size() || std::abs(Area(region) - like_area) > 0.25 * like_area)) {
      continue;
    }
    const Eigen::Vector2d c = Centroid(region);
    if (c.norm() < best) {
      best = c.norm();
      layer.section = region;
      layer.centroid_P = layer.ToPart(c);
      cut.found = true;
    }
  }
  return cut;
}

// Mid-wall curve: the outer ring moved inwards by half the wall (Clipper, round joins); the longest ring of the result.
Ring MidCurve(const PolygonWithHoles& section, double wall_mm) {
  const std::vector<PolygonWithHoles> offset = internal::Offset({PolygonWithHoles{section.outer, {}}}, -0.5 * wall_mm);
  Ring best;
  for (const PolygonWithHoles& region : offset) {
    if (Perimeter(region.outer) > Perimeter(best)) best = region.outer;
  }
  if (SignedArea(best) < 0.0) std::reverse(best.begin(), best.end());
  return best;
}

// Wall thickness of a hollow cut: area / mean of the outer and inner perimeters; 0 for a solid cut.
double EstimateWall(const PolygonWithHoles& section) {
  if (section.holes.empty()) return 0.0;
  double inner = 0.0;
  for (const Ring& hole : section.holes) inner += Perimeter(hole);
  return Area(section) / (0.5 * (Perimeter(section.outer) + inner));
}

// Thickness range of the layer under `top`: distances of its mid curve to the plane of `below`.
void MeasureThickness(const SkeletonLayer& below, SkeletonLayer* top) {
  top->min_height_mm = std::numeric_limits<double>::infinity();
  top->max_height_mm = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& q : top->mid_curve) {
    const double h = (top->ToPart(q) - below.centroid_P).dot(below.normal_P);
    top->min_height_mm = std::min(top->min_height_mm, h);
    top->max_height_mm = std::max(top->max_height_mm, h);
  }
}

constexpr double kMaxTurnRad = 10.0 * kPi / 180.0;

double AngleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// The accepted range of a layer's thickness: h_min and h_max widened by the tolerance, mm.
struct SliceStep {
  double lo = 0.0, hi = 0.0;
};

constexpr double kBaseCutMm = 1e-3;  // the base cut's height above the substrate, and the end layer's margin, mm

// The base: the cut just above the substrate, with its centroid put on z = 0; sets *wall_mm (slicing.wall_mm, or
// the base section's estimated wall). Throws InputError when there is no such cut or the base is solid.
SkeletonLayer BaseLayer(const TriangleMesh& mesh, const SkeletonSliceOptions& options, double* wall_mm) {
  Cut base = CutPlane(mesh, Eigen::Vector3d(0.0, 0.0, kBaseCutMm), Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                      std::numeric_limits<double>::infinity());
  WAAM_THROW_UNLESS(base.found, "skeleton slicing: the part has no section just above the substrate (z = 0)");
  *wall_mm = options.wall_mm > 0.0 ? options.wall_mm : EstimateWall(base.layer.section);
  WAAM_THROW_UNLESS(*wall_mm > 0.0, "skeleton slicing: the base section is solid; give slicing.wall_mm for the "
                                    "mid-wall path of a solid part");
  base.layer.origin_P.z() = 0.0;
  base.layer.centroid_P.z() = 0.0;
  base.layer.mid_curve = MidCurve(base.layer.section, *wall_mm);
  return base.layer;
}

// The cut through G along `direction`, re-oriented about G perpendicular to V until gamma = angle(N, V) <= beta
// (eq. 5.24-5.26). V is taken between the centroids of two parallel cuts, through I_i and through G, both with the
// candidate normal: an oblique cut of a tapered section shifts its centroid towards the wide side, and measured from
// I_i of the plane below that shift feeds back into the next tilt (on a cone the plane would run away); two parallel
// cuts shift alike and the bias cancels.
Cut OrientedCut(const TriangleMesh& mesh, const SkeletonLayer& below, const Eigen::Vector3d& G,
                const Eigen::Vector3d& direction, double reach, const SkeletonSliceOptions& options) {
  Cut cut = CutPlane(mesh, G, direction, below.e1_P, reach, &below.section);
  for (int turn = 0; cut.found && turn < options.max_iterations; ++turn) {
    Eigen::Vector3d I_below = below.centroid_P;
    if (AngleBetween(cut.layer.normal_P, below.normal_P) > 1e-9) {
      const Cut parallel = CutPlane(mesh, below.centroid_P, cut.layer.normal_P, below.e1_P, reach, &below.section);
      if (parallel.found) I_below = parallel.layer.centroid_P;
    }
    const Eigen::Vector3d V = (cut.layer.centroid_P - I_below).normalized();
    if (AngleBetween(cut.layer.normal_P, V) <= options.beta_rad) break;
    // A plane turned more than kMaxTurnRad from the last one is not following the axis (e.g. near an end face).
    if (AngleBetween(direction, V) > kMaxTurnRad) break;
    Cut turned = CutPlane(mesh, G, V, below.e1_P, reach, &below.section);
    if (!turned.found) break;
    cut = turned;
  }
  return cut;
}

// The layer above `below`: the step h' along `direction` scaled until its thickness is within `limits` (Fig. 56),
// at most options.max_iterations rounds; *step is the step taken. std::nullopt past the part's top.
std::optional<SkeletonLayer> NextLayer(const TriangleMesh& mesh, const SkeletonLayer& below,
                                       const SkeletonSliceOptions& options, double wall_mm, const SliceStep& limits,
                                       const Eigen::Vector3d& direction, double reach, double* step) {
  std::optional<SkeletonLayer> accepted;
  for (int round = 0; round < options.max_iterations; ++round) {
    const Eigen::Vector3d G = below.centroid_P + *step * direction;
    Cut cut = OrientedCut(mesh, below, G, direction, reach, options);
    if (!cut.found) break;
    cut.layer.mid_curve = MidCurve(cut.layer.section, wall_mm);
    if (cut.layer.mid_curve.size() < 3) break;
    cut.layer.step_mm = *step;
    MeasureThickness(below, &cut.layer);
    if (cut.layer.min_height_mm <= 0.0) break;  // the plane crosses the one below: not a layer
    accepted = cut.layer;
    // Fig. 56: scale h' up when the thinnest point is below h_min, down when the thickest is above h_max.
    if (cut.layer.min_height_mm < limits.lo && cut.layer.min_height_mm > 0.0) {
      *step *= options.h_min_mm / cut.layer.min_height_mm;
    } else if (cut.layer.max_height_mm > limits.hi) {
      *step *= options.h_max_mm / cut.layer.max_height_mm;
    } else {
      break;
    }
    *step = std::clamp(*step, 0.25 * options.h_min_mm, 2.0 * options.h_max_mm);
  }
  return accepted;
}

// Past the top: a last, thinner layer up to the end face when it is at least half of h_min thick, appended to out.
void AddEndLayer(const TriangleMesh& mesh, const SkeletonLayer& below, const SkeletonSliceOptions& options,
                 const SliceStep& limits, const Eigen::Vector3d& direction, double reach, double step,
                 SkeletonSlicing* out) {
  double a = 0.0, b = step;
  for (int k = 0; k < 20; ++k) {
    const double mid = 0.5 * (a + b);
    (CutPlane(mesh, below.centroid_P + mid * direction, direction, below.e1_P, reach, &below.section).found ? a : b) =
        mid;
  }
  const double last = a - kBaseCutMm;
  if (last < 0.5 * options.h_min_mm) return;
  Cut cut = CutPlane(mesh, below.centroid_P + last * direction, direction, below.e1_P, reach, &below.section);
  if (!cut.found) return;
  cut.layer.mid_curve = MidCurve(cut.layer.section, out->wall_mm);
  cut.layer.step_mm = last;
  if (cut.layer.mid_curve.size() < 3) return;
  MeasureThickness(below, &cut.layer);
  cut.layer.in_range = cut.layer.max_height_mm <= limits.hi;  // the end layer may be thinner than h_min
  if (!cut.layer.in_range) ++out->out_of_range_layers;
  out->layers.push_back(cut.layer);
}

}  // namespace

void SkeletonSliceOptions::Validate(const std::string& where) const {
  WAAM_THROW_UNLESS(h_min_mm > 0.0 && std::isfinite(h_min_mm),
                    where << ".h_min_mm = " << h_min_mm << ": must be > 0");
  WAAM_THROW_UNLESS(h_max_mm >= h_min_mm && std::isfinite(h_max_mm),
                    where << ".h_max_mm = " << h_max_mm << ": must be >= h_min_mm = " << h_min_mm);
  WAAM_THROW_UNLESS(first_step_mm >= 0.0, where << ".first_step_mm = " << first_step_mm << ": must be >= 0");
  WAAM_THROW_UNLESS(beta_rad > 0.0, where << ".beta_deg = " << beta_rad * 180.0 / kPi << ": must be > 0");
  WAAM_THROW_UNLESS(wall_mm >= 0.0, where << ".wall_mm = " << wall_mm << ": must be >= 0");
}

double MinimumBendRadius(double d_mm, double h_min_mm, double h_max_mm) {
  // eq. 6.3: alpha = h_min / R1 = h_max / R2 with R1 = R - d/2, R2 = R + d/2, so (R + d/2) / (R - d/2) = lambda.
  const double lambda = h_max_mm / h_min_mm;
  if (lambda <= 1.0) return std::numeric_limits<double>::infinity();
  return 0.5 * d_mm * (lambda + 1.0) / (lambda - 1.0);
}

SkeletonSlicing SliceAlongSkeleton(const TriangleMesh& mesh, const SkeletonSliceOptions& options, Progress* progress) {
  options.Validate("slicing");
  SkeletonSlicing out;
  double z_top = 0.0;
  for (const Eigen::Vector3d& v : mesh.vertices) z_top = std::max(z_top, v.z());
  out.base = BaseLayer(mesh, options, &out.wall_mm);
  const SliceStep limits{options.h_min_mm * (1.0 - options.tolerance), options.h_max_mm * (1.0 + options.tolerance)};
  double step = options.first_step_mm > 0.0 ? options.first_step_mm : 0.5 * (options.h_min_mm + options.h_max_mm);
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // N_i = V_(i-1) (eq. 5.23)
  // The layer count (the base and the layers above it, as the plan has them) is not known before the slicing:
  // estimated from the part's height, raised whenever a bent axis (longer than the height) yields more, and set to
  // the count at the end.
  std::size_t expected_layers = static_cast<std::size_t>(z_top / options.h_min_mm) + 2;
  if (progress) progress->SetTotal(expected_layers);
  while (true) {
    const SkeletonLayer& below = out.layers.empty() ? out.base : out.layers.back();
    // Reach: the next centroid lies within about half a section of the guess G.
    const double reach = std::max(5.0, 0.5 * Perimeter(below.section.outer) / kPi + 2.0 * options.h_max_mm);
    std::optional<SkeletonLayer> accepted =
        NextLayer(mesh, below, options, out.wall_mm, limits, direction, reach, &step);
    if (!accepted) {
      AddEndLayer(mesh, below, options, limits, direction, reach, step, &out);
      break;
    }
    accepted->in_range = accepted->min_height_mm >= limits.lo && accepted->max_height_mm <= limits.hi;
    if (!accepted->in_range) ++out.out_of_range_layers;
    // eq. 5.23: the next plane starts along this layer's V, which the re-orientation made its normal (gamma <= beta).
    direction = accepted->normal_P;
    out.layers.push_back(*accepted);
    if (progress) {
      if (out.layers.size() + 1 >= expected_layers) progress->SetTotal(expected_layers = out.layers.size() + 2);
      progress->Update(out.layers.size() + 1);
    }
    WAAM_THROW_UNLESS(out.layers.size() < 20000, "skeleton slicing: more than 20000 layers; check the units");
  }
  if (progress) {
    progress->SetTotal(out.layers.size() + 1);
    progress->Finish();
  }
  return out;
}

std::vector<Eigen::Vector3d> CentroidChain(const SkeletonSlicing& slicing) {
  std::vector<Eigen::Vector3d> chain{slicing.base.centroid_P};
  for (const SkeletonLayer& layer : slicing.layers) chain.push_back(layer.centroid_P);
  return chain;
}

BendEstimate EstimateTightestBend(const SkeletonSlicing& slicing, int window) {
  BendEstimate best;
  best.radius_mm = std::numeric_limits<double>::infinity();
  const std::vector<Eigen::Vector3d> chain = CentroidChain(slicing);
  auto normal = [&](int i) { return i == 0 ? slicing.base.normal_P : slicing.layers[i - 1].normal_P; };
  const int n = static_cast<int>(chain.size());
  for (int i = 0; i + 2 * window < n; ++i) {
    const int j = i + 2 * window;
    const double angle = AngleBetween(normal(i), normal(j));
    if (angle < 1e-3) continue;
    double arc = 0.0;
    for (int k = i; k < j; ++k) arc += (chain[k + 1] - chain[k]).norm();
    const double radius = arc / angle;
    if (radius >= best.radius_mm) continue;
    // Extent of the middle layer's mid curve along the direction the axis turns towards.
    const int mid = i + window;
    const SkeletonLayer& layer = mid == 0 ? slicing.base : slicing.layers[mid - 1];
    Eigen::Vector3d towards = normal(j) - normal(i);
    towards -= towards.dot(layer.normal_P) * layer.normal_P;
    if (towards.norm() < 1e-12) continue;
    towards.normalize();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Eigen::Vector2d& q : layer.mid_curve) {
      const double x = layer.ToPart(q).dot(towards);
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
    best.radius_mm = radius;
    best.extent_mm = hi - lo;
    best.layer = mid;
  }
  return best;
}

}  // namespace waam::planner
