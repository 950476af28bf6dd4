// Cone/cylinder slicing of Dai et al. 2020 sec. 2.1: edge points from eq. 1 with eq. 2, one to three segments per
// facet, segments merged into closed contours (steps 0-4 of sec. 2.1.2); and the flattening of a layer (sec. 2.2).
#include "planner/slicing/cone_slicer.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "models/core/numbers.h"
#include "planner/geometry/clipper_adapter.h"

namespace waam::planner {
namespace {

// A vertex closer than this to the surface counts as "on" it (step 0): the surface radius is nudged instead.
constexpr double kOnSurfaceMm = 1e-7;

// Roots t in (0, 1) of eq. 1 along the edge p(t) = t p1 + (1 - t) p0 (eq. 2), on the real nappe (z/H < 1), sorted.
std::vector<double> EdgeRoots(const ConeSurface& s, const Eigen::Vector3d& p0_P, const Eigen::Vector3d& p1_P) {
  const Eigen::Vector3d q0 = p0_P - s.axis_P;
  const Eigen::Vector3d e = p1_P - p0_P;
  const double k = s.cylinder() ? 0.0 : s.R / s.H;
  // x^2 + y^2 - k^2 (z - H)^2 = 0 (cylinder: x^2 + y^2 - R^2 = 0) with x = x0 + t ex, ... gives a t^2 + b t + c.
  const double zh = s.cylinder() ? 0.0 : q0.z() - s.H;
  const double a = e.x() * e.x() + e.y() * e.y() - k * k * e.z() * e.z();
  const double b = 2.0 * (q0.x() * e.x() + q0.y() * e.y() - k * k * zh * e.z());
  const double c = s.Residual(p0_P);
  std::vector<double> roots;
  const double scale = std::max({std::abs(a), std::abs(b), std::abs(c), 1e-300});
  if (std::abs(a) < 1e-14 * scale) {
    if (std::abs(b) > 1e-14 * scale) roots.push_back(-c / b);
  } else {
    const double disc = b * b - 4.0 * a * c;
    if (disc >= 0.0) {
      // Numerically stable pair of roots.
      const double qq = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      roots.push_back(qq / a);
      if (qq != 0.0) roots.push_back(c / qq);
    }
  }
  std::vector<double> kept;
  for (double t : roots) {
    if (!(t > 0.0 && t < 1.0)) continue;
    const double z = q0.z() + t * e.z();
    if (!s.cylinder() && z / s.H >= 1.0) continue;  // the other nappe, past the apex
    kept.push_back(t);
  }
  std::sort(kept.begin(), kept.end());
  // The number of crossings must match the sides of the end points; fix what rounding broke.
  const bool out0 = s.NormalOffset(p0_P) > 0.0;
  const bool out1 = s.NormalOffset(p1_P) > 0.0;
  if ((kept.size() % 2 == 1) != (out0 != out1)) {
    if (kept.empty()) {
      const double f0 = s.NormalOffset(p0_P);
      const double f1 = s.NormalOffset(p1_P);
      kept.push_back(std::clamp(f0 / (f0 - f1), 1e-9, 1.0 - 1e-9));
    } else {
      kept.pop_back();
    }
  }
  return kept;
}

struct Slicing {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> neighbours;
};

// One pass of the intersection; returns false (without result) if a vertex lies on the surface.
bool TrySlice(const TriangleMesh& mesh, const ConeSurface& s, Slicing* out, ConeSliceStats* stats) {
  for (const Eigen::Vector3d& v : mesh.vertices) {
    if (std::abs(s.NormalOffset(v)) < kOnSurfaceMm) return false;
  }
  // Edge points, each edge once, stored from its lower to its higher vertex index.
  std::map<std::pair<int, int>, std::vector<int>> edge_points;
  auto points_of = [&](int a, int b) -> std::vector<int> {
    const std::pair<int, int> key(std::min(a, b), std::max(a, b));
    auto it = edge_points.find(key);
    if (it == edge_points.end()) {
      std::vector<int> ids;
      const Eigen::Vector3d& p0 = mesh.vertices[key.first];
      const Eigen::Vector3d& p1 = mesh.vertices[key.second];
      for (double t : EdgeRoots(s, p0, p1)) {
        ids.push_back(static_cast<int>(out->points.size()));
        out->points.push_back(t * p1 + (1.0 - t) * p0);  // eq. 2
      }
      it = edge_points.emplace(key, std::move(ids)).first;
    }
    std::vector<int> ids = it->second;
    if (a > b) std::reverse(ids.begin(), ids.end());
    return ids;
  };
  std::vector<std::pair<int, int>> segments;
  for (const auto& f : mesh.facets) {
    // The crossings in order round the facet boundary, starting at vertex f[0].
    std::vector<int> ring;
    for (int e = 0; e < 3; ++e) {
      for (int id : points_of(f[e], f[(e + 1) % 3])) ring.push_back(id);
    }
    const std::size_t n = ring.size();
    if (n == 0) {
      ++stats->facets_with_segments[0];
      continue;
    }
    // Step 0. The solid inside a single nappe (r <= R (1 - z/H)) is convex, so its part in the facet is one convex
    // piece whose boundary runs along the facet between crossings and along the surface from a crossing to the
    // next one round the facet: the segments join consecutive crossings that enclose an OUTSIDE stretch of the
    // facet boundary. This gives Dai's pairing (pairs do not cross and, for 4 or 6 points, join different edges;
    // Fig. 3(b)) from the sides of the vertices alone.
    const bool start_outside = s.NormalOffset(mesh.vertices[f[0]]) > 0.0;
    const std::size_t first = start_outside ? 1 : 0;
    for (std::size_t j = 0; j + 1 < n + 1; j += 2) {
      segments.emplace_back(ring[(first + j) % n], ring[(first + j + 1) % n]);
    }
    ++stats->facets_with_segments[std::min<std::size_t>(3, n / 2)];
  }
  out->neighbours.assign(out->points.size(), {});
  for (const auto& [a, b] : segments) {
    out->neighbours[a].push_back(b);
    out->neighbours[b].push_back(a);
  }
  stats->edge_points = out->points.size();
  return true;
}

}  // namespace

std::vector<Contour3d> SliceWithCone(const TriangleMesh& mesh, const ConeSurface& surface, ConeSliceStats* stats) {
  ConeSliceStats local;
  if (!stats) stats = &local;
  *stats = ConeSliceStats{};
  ConeSurface s = surface;
  Slicing slicing;
  // Step 0 deletes intersection points on vertices; nudging the surface off every vertex (by far less than any
  // tolerance of the process) does the same without special cases.
  for (int attempt = 0; !TrySlice(mesh, s, &slicing, stats); ++attempt) {
    slicing = Slicing{};
    *stats = ConeSliceStats{};
    s.R += 1e-6 * (attempt + 1);
    stats->surface_shift_mm = s.R - surface.R;
  }
  // Steps 1-4: start at an unused point, follow the segment chain until it returns to the start; repeat.
  std::vector<Contour3d> contours;
  std::vector<bool> used(slicing.points.size(), false);
  for (std::size_t start = 0; start < slicing.points.size(); ++start) {
    if (used[start]) continue;
    Contour3d contour;
    int previous = -1;
    int current = static_cast<int>(start);
    bool closed = false;
    while (true) {
      used[current] = true;
      contour.push_back(slicing.points[current]);
      int next = -1;
      for (int n : slicing.neighbours[current]) {
        if (n != previous && (!used[n] || (n == static_cast<int>(start) && contour.size() > 2))) {
          next = n;
          break;
        }
      }
      if (next < 0) {
        // Two crossings on one edge joined by both of its facets: the surface only grazes the edge.
        closed = contour.size() == 2 && slicing.neighbours[current].size() == 2 &&
                 slicing.neighbours[current][0] == slicing.neighbours[current][1];
        if (closed) contour.clear();
        break;
      }
      if (next == static_cast<int>(start)) {
        closed = true;
        break;
      }
      previous = current;
      current = next;
    }
    if (closed && contour.empty()) continue;
    if (!closed || slicing.neighbours[start].size() != 2) {
      ++stats->open_chains;
      continue;
    }
    // Drop repeated points (two crossings at the same place).
    Contour3d clean;
    for (const Eigen::Vector3d& p : contour) {
      if (clean.empty() || (p - clean.back()).norm() > 1e-9) clean.push_back(p);
    }
    while (clean.size() > 1 && (clean.front() - clean.back()).norm() <= 1e-9) clean.pop_back();
    if (clean.size() >= 3) contours.push_back(std::move(clean));
  }
  return contours;
}

FlatLayer FlattenLayer(const std::vector<Contour3d>& contours, const ConeSurface& surface, double step_rad) {
  FlatLayer out;
  // A contour that winds round the axis cannot be flattened in one piece whatever the rotation.
  for (std::size_t c = 0; c < contours.size(); ++c) {
    double winding = 0.0;
    const Contour3d& contour = contours[c];
    for (std::size_t j = 0; j < contour.size(); ++j) {
      const double a = surface.Theta(contour[j], 0.0);
      const double b = surface.Theta(contour[(j + 1) % contour.size()], 0.0);
      winding += std::remainder(b - a, 2.0 * kPi);
    }
    if (std::abs(winding) > kPi) {
      out.message = "contour " + std::to_string(c) + " winds round the surface axis; the developable flattening " +
                    "needs contours that a cutting line can miss (Dai sec. 2.2)";
      return out;
    }
  }
  // Sec. 2.2: try alpha = 0, 11, 22, ... deg until the cutting line (theta = +-pi after the turn) misses every
  // contour. Dai turns the contour nearest the cutting line; one alpha for the whole layer keeps every region of
  // the layer in one flat frame, so holes stay inside their outers.
  const int tries = std::max(1, static_cast<int>(std::floor(2.0 * kPi / step_rad - 1e-9)) + 1);
  for (int k = 0; k < tries && !out.ok; ++k) {
    const double alpha = k * step_rad;
    bool crosses = false;
    for (const Contour3d& contour : contours) {
      for (std::size_t j = 0; j < contour.size() && !crosses; ++j) {
        const double a = surface.Theta(contour[j], alpha);
        const double b = surface.Theta(contour[(j + 1) % contour.size()], alpha);
        crosses = std::abs(b - a) > kPi;
      }
      if (crosses) break;
    }
    if (!crosses) {
      out.ok = true;
      out.alpha = alpha;
    }
  }
  if (!out.ok) {
    out.message = "every rotation in steps of " + std::to_string(step_rad * 180.0 / kPi) +
                  " deg leaves a contour across the cutting line";
    return out;
  }
  ClipperLib::Paths paths;
  for (const Contour3d& contour : contours) {
    Ring ring;
    for (const Eigen::Vector3d& p : contour) ring.push_back(surface.Flatten(p, out.alpha));
    if (std::abs(SignedArea(ring)) < 1e-6) continue;
    paths.push_back(internal::ToPath(ring, true));
  }
  ClipperLib::Clipper clipper;
  clipper.AddPaths(paths, ClipperLib::ptSubject, true);
  ClipperLib::PolyTree tree;
  clipper.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftEvenOdd, ClipperLib::pftEvenOdd);
  out.regions = internal::FromPolyTree(tree);
  return out;
}

}  // namespace waam::planner
