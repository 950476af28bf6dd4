// The decomposition algorithm of the dissertation (003 sec. 5.4): z slices simplified to their outer sections
// (Fig. 53), each region followed to the slice above it, overhang pieces found by projecting the bottom layer onto
// the top layer (Fig. 57), kept as features when their centroid chain leans (eq. 5.25-5.26), and split off by the
// plane through their first and last split lines.
#include "planner/slicing/centroid_decomposition.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "models/core/progress.h"
#include "planner/geometry/clipper_adapter.h"
#include "planner/mesh/mesh_ops.h"
#include "planner/slicing/planar_slicer.h"

namespace waam::planner {
namespace {

constexpr double kSliverMm2 = 1e-3;      // smaller pieces are numerical leftovers of the booleans
constexpr double kContactStepMm = 0.05;  // split-line points are taken along the contact outline this densely
using Regions = std::vector<PolygonWithHoles>;

// Area-weighted centroid (mm) and area (mm^2) of regions; holes count negative.
std::pair<Eigen::Vector2d, double> CentroidOf(const Regions& regions) {
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  double area = 0.0;
  auto add = [&](const Ring& ring, double sign) {
    // Shoelace: A = 1/2 sum x_i y_(i+1) - x_(i+1) y_i, A c = 1/6 sum (p_i + p_(i+1)) (x_i y_(i+1) - x_(i+1) y_i).
    const double orient = SignedArea(ring) >= 0.0 ? sign : -sign;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Eigen::Vector2d& p = ring[i];
      const Eigen::Vector2d& q = ring[(i + 1) % ring.size()];
      const double cross = p.x() * q.y() - q.x() * p.y();
      area += orient * 0.5 * cross;
      moment += orient * (p + q) * cross / 6.0;
    }
  };
  for (const PolygonWithHoles& r : regions) {
    add(r.outer, 1.0);
    for (const Ring& h : r.holes) add(h, -1.0);
  }
  return {area > 0.0 ? Eigen::Vector2d(moment / area) : Eigen::Vector2d::Zero(), area};
}

// Simplification module (Fig. 53): only the outer sections count; an island in a hole merges into its outer.
Regions OuterOnly(const Regions& slice) {
  Regions outers;
  for (const PolygonWithHoles& r : slice) outers.push_back({r.outer, {}});
  return internal::Union(outers);
}

void Append(const Regions& more, Regions* regions) { regions->insert(regions->end(), more.begin(), more.end()); }

// A region followed through the slices: the body (label 0) or an overhang candidate.
struct Track {
  int parent = 0;
  std::map<int, Regions> slices;  // slice index -> its regions there
  std::vector<std::pair<int, std::vector<Eigen::Vector2d>>> contacts;  // split lines: slice index, points (mm)
};

// A split line (Fig. 57c) as a point and a unit direction in the slice plane (principal axis of its points).
std::pair<Eigen::Vector2d, Eigen::Vector2d> FitLine(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& p : points) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  return {mean, eig.eigenvectors().col(1)};
}

// The regions of one slice's outer sections `top` by label: each continues the label it stands on in `previous`
// (the uniform and not-uniform cases of Fig. 54b-c); self-supporting growth (a step out of at most `delta`) goes to
// the label whose grown bottom covers most of it; an overhang piece (A2, A3 of Fig. 57c) joins the feature it
// touches (closer than `gap`), else starts a new candidate track.
std::map<int, Regions> AssignRegions(const Regions& top, const std::map<int, Regions>& previous, double delta,
                                     double gap, double min_area_mm2, std::vector<Track>* tracks) {
  std::map<int, Regions> assigned;
  if (previous.empty()) {
    if (!top.empty()) assigned[0] = top;  // the bottom layer (or a restart on the plate) belongs to the body
    return assigned;
  }
  Regions remaining = top;
  Regions bottom;
  for (const auto& [label, regions] : previous) {
    Regions on = internal::Intersection(remaining, regions);
    if (on.empty()) continue;
    Append(on, &assigned[label]);
    remaining = internal::Difference(remaining, regions);
  }
  for (const auto& [label, regions] : previous) Append(regions, &bottom);
  const Regions projected = internal::Offset(internal::Union(bottom), delta);  // Fig. 57a, grown by delta
  for (const PolygonWithHoles& piece : remaining) {
    if (Area(piece) < kSliverMm2) continue;  // Clipper's zero-area leftovers along shared edges
    const Regions x = {piece};
    const double unsupported = Area(internal::Difference(x, projected));
    if (unsupported < min_area_mm2) {
      int best = 0;
      double best_area = 0.0;
      for (const auto& [label, regions] : previous) {
        const double a = Area(internal::Intersection(x, internal::Offset(regions, delta)));
        if (a > best_area) {
          best = label;
          best_area = a;
        }
      }
      Append(x, &assigned[best]);
      continue;
    }
    const Regions grown = internal::Offset(x, gap);
    int feature = -1;
    int touched = -1;
    for (const auto& [label, regions] : assigned) {
      if (internal::Intersection(grown, regions).empty()) continue;
      if (label > 0) {
        feature = label;
        break;
      }
      touched = label;
    }
    if (feature < 0) {
      tracks->push_back(Track{std::max(touched, 0), {}, {}});
      feature = static_cast<int>(tracks->size()) - 1;
    }
    Append(x, &assigned[feature]);
  }
  return assigned;
}

// Slice j's regions by label merged (slivers dropped) and kept in their tracks, with the split lines (Fig. 57c)
// where a candidate meets its parent in this slice.
void RecordSlice(int j, double gap, std::map<int, Regions>* assigned, std::vector<Track>* tracks) {
  for (auto it = assigned->begin(); it != assigned->end();) {
    it->second = internal::Union(it->second);
    std::erase_if(it->second, [](const PolygonWithHoles& r) { return Area(r) < kSliverMm2; });
    if (it->second.empty()) {
      it = assigned->erase(it);
      continue;
    }
    (*tracks)[it->first].slices[j] = it->second;
    ++it;
  }
  for (const auto& [label, regions] : *assigned) {
    if (label == 0) continue;
    const auto parent = assigned->find((*tracks)[label].parent);
    if (parent == assigned->end()) continue;
    const Regions contact =
        internal::Intersection(internal::Offset(regions, gap), internal::Offset(parent->second, gap));
    // Points evenly along the outline, so that the fitted line does not lean towards where Clipper put more
    // vertices (round joins).
    std::vector<Eigen::Vector2d> points;
    for (const PolygonWithHoles& r : contact) {
      for (std::size_t i = 0; i < r.outer.size(); ++i) {
        const Eigen::Vector2d& p = r.outer[i];
        const Eigen::Vector2d& q = r.outer[(i + 1) % r.outer.size()];
        const int steps = std::max(1, static_cast<int>(std::ceil((q - p).norm() / kContactStepMm)));
        for (int k = 0; k < steps; ++k) points.push_back(p + (q - p) * (static_cast<double>(k) / steps));
      }
    }
    if (points.size() >= 2) (*tracks)[label].contacts.emplace_back(j, std::move(points));
  }
}

// The overhang feature of a candidate track, with its split plane through the first and last split lines (sec. 5.4,
// decomposition module); false when it leans no more than a wall may and stays with the body. `heights`: the slice
// heights, `h` their spacing, mm. Throws InputError when the overhang never meets the body.
bool OverhangOf(const Track& track, const std::vector<double>& heights, double h, double overhang_deg,
                const std::string& where, OverhangFeature* out) {
  OverhangFeature& f = *out;
  // Centroid chain I_i (eq. 5.25: V_i = I_(i+1) - I_i) and its angle to the body's direction N = +z (eq. 5.26).
  double area_sum = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  std::pair<int, Eigen::Vector2d> last{-2, Eigen::Vector2d::Zero()};
  for (const auto& [j, regions] : track.slices) {
    const auto [c, area] = CentroidOf(regions);
    if (area <= 0.0) continue;
    if (last.first == j - 1) {
      f.max_gamma_deg = std::max(f.max_gamma_deg, std::atan2((c - last.second).norm(), h) * 180.0 / kPi);
    }
    last = {j, c};
    area_sum += area;
    moment += area * Eigen::Vector3d(c.x(), c.y(), heights[j]);
  }
  if (area_sum <= 0.0 || f.max_gamma_deg <= overhang_deg) return false;
  f.centroid_mm = moment / area_sum;
  f.volume_mm3 = area_sum * h;
  f.z_min_mm = heights[track.slices.begin()->first];
  f.z_max_mm = heights[track.slices.rbegin()->first];
  WAAM_THROW_UNLESS(!track.contacts.empty(),
                    where << ": an overhang from z = " << f.z_min_mm << " to " << f.z_max_mm
                          << " mm never meets the body in a slice: no split plane can cut it off");
  const auto& [j1, points1] = track.contacts.front();
  const auto& [j2, points2] = track.contacts.back();
  const auto [m1, d1] = FitLine(points1);
  auto [m2, d2] = FitLine(points2);
  if (d1.dot(d2) < 0.0) d2 = -d2;
  const Eigen::Vector3d d = Eigen::Vector3d(d1.x() + d2.x(), d1.y() + d2.y(), 0.0).normalized();
  const Eigen::Vector3d p1(m1.x(), m1.y(), heights[j1]);
  const Eigen::Vector3d p2(m2.x(), m2.y(), heights[j2]);
  Eigen::Vector3d n = d.cross(p2 - p1);
  if (j1 == j2 || n.norm() < 1e-3 * (p2 - p1).norm()) n = d.cross(Eigen::Vector3d::UnitZ());  // one split line
  n.normalize();
  const Eigen::Vector3d centre = 0.5 * (p1 + p2);
  if (n.dot(f.centroid_mm - centre) < 0.0) n = -n;
  f.split_normal = n;
  f.split_offset_mm = n.dot(centre);
  f.axis = (f.centroid_mm - centre).normalized();
  return true;
}

}  // namespace

CentroidDecomposition DecomposeByCentroidShift(const TriangleMesh& mesh, const CentroidSplitOptions& options,
                                               const std::string& where) {
  WAAM_THROW_UNLESS(std::isfinite(options.step_mm) && options.step_mm > 0.0,
                    where << ".layer_height_mm = " << options.step_mm << ": must be > 0");
  WAAM_THROW_UNLESS(options.overhang_deg > 0.0 && options.overhang_deg < 90.0,
                    where << ".overhang_deg = " << options.overhang_deg << ": must be in (0, 90) deg");
  Eigen::Vector3d lo, hi;
  BoundingBox(mesh, &lo, &hi);
  const int count = std::max(1, static_cast<int>(std::lround((hi.z() - lo.z()) / options.step_mm)));
  const double h = (hi.z() - lo.z()) / count;
  std::vector<double> heights(count);
  for (int j = 0; j < count; ++j) heights[j] = lo.z() + (j + 0.5) * h;
  const std::vector<Regions> slices = SlicePlanar(mesh, heights);

  // A layer may step out t tan(overhang) past the layer below and still stand on it; pieces of the same slice
  // closer than half a step touch (shells that meet in the mesh, or nearly).
  const double tan_overhang = std::tan(options.overhang_deg * kPi / 180.0);
  const double delta = h * tan_overhang;
  const double gap = 0.5 * h;
  std::vector<Track> tracks(1);
  std::map<int, Regions> previous;  // label -> regions of the slice below
  for (int j = 0; j < count; ++j) {
    CheckInterrupt();
    std::map<int, Regions> assigned =
        AssignRegions(OuterOnly(slices[j]), previous, delta, gap, options.min_area_mm2, &tracks);
    RecordSlice(j, gap, &assigned, &tracks);
    previous = std::move(assigned);
  }

  CentroidDecomposition result;
  result.slices = count;
  SubVolumeSpec body{"body", {0.0, 0.0, 1.0}, {}};
  for (std::size_t k = 1; k < tracks.size(); ++k) {
    OverhangFeature f;
    if (!OverhangOf(tracks[k], heights, h, options.overhang_deg, where, &f)) {
      ++result.candidates_merged;  // stays with the body: it leans no more than a wall may
      continue;
    }
    f.name = "overhang_" + std::to_string(result.features.size() + 1);
    body.keep.push_back({f.split_normal.x(), f.split_normal.y(), f.split_normal.z(), f.split_offset_mm});
    result.features.push_back(f);
  }
  result.sub_volumes.push_back(body);
  for (const OverhangFeature& f : result.features) {
    const Eigen::Vector3d& n = f.split_normal;
    result.sub_volumes.push_back({f.name, {n.x(), n.y(), n.z()}, {{-n.x(), -n.y(), -n.z(), -f.split_offset_mm}}});
  }
  return result;
}

}  // namespace waam::planner
