// Notch-elimination convex decomposition of slice regions (Ding et al. 2014, section 3.1).
//
// Differences from the paper, on purpose:
// - Orientation: outer boundaries are counter-clockwise and holes clockwise (Ding step 2 uses the opposite); the
//   interior is always on the left, so a notch is a right turn. The interior angle is phi = pi - turn, with the
//   turn from atan2 of the cross and dot products of the two edges: the same quadrant-correct angle as eq. (1)-(2).
// - Scan zone: Ding looks at the vertices "along the geometry edges from A_i to B_i", the two points where the
//   extensions of the notch's edges hit the boundary. On polygons with holes that chain is not well defined, so the
//   scan zone here is: every vertex (of the outline or of any hole) strictly inside the cone between the two edge
//   extensions and visible from the notch (the cut crosses no edge). Among them a notch nearest to the bisector line
//   is taken first (notch-notch), else a vertex nearest to the bisector (notch-vertex), else the bisector is cast to
//   the first edge it meets (notch-line). Every such cut leaves angles < pi at the reference notch, so each cut
//   removes at least one notch and the loop ends after at most (number of notches) cuts.
// - Holes: Ding merges an island into the outline with a merging line before splitting (his Fig. 5 a->b). Here a
//   hole vertex is a notch like any other (its interior angle, seen from the region, is > pi); when the largest
//   notch's cut lands on a different boundary (outline <-> hole, hole <-> hole) it becomes the merging line: the
//   two cycles are joined into one weakly simple cycle that runs along both sides of the cut. A cut that lands on
//   its own cycle is a split line and yields two regions; holes go to the piece that contains them.
// - Afterwards, two pieces that share a whole edge are merged when their union is still convex (a cut that a later
//   cut made unnecessary), thinnest first: fewer pieces, fewer slivers without a path of their own.
// - Slivers: Ding notes the method suits few round holes badly. Its weakness is the notch-vertex routine: the
//   notches of a round hole all see the same far corner and cut to it, leaving a fan of slivers narrower than a
//   bead. A vertex is therefore only a candidate if the cut makes an angle >= 45 degrees with the boundary edges at
//   that vertex; the notch-line routine likewise tilts the bisector (within the cone) away from grazing hits.
// - Noise: Ding's notch test phi > pi is exact. Here input vertices within 1 um of the line through their neighbours
//   are dropped first (kStraightToleranceMm), so a sliced disc whose edge points sit a rounding error inside the
//   edge is one convex piece, not a fan of slivers.
#include "planner/geometry/convex_decomposition.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <Eigen/Geometry>

#include "models/core/error.h"
#include "planner/geometry/ring_math.h"

namespace waam::planner {
namespace {

using internal::At;
using internal::BoundingDiagonal;
using internal::Cross;
using internal::Turn;

using Vec = Eigen::Vector2d;

constexpr double kSinTolerance = 1e-7;  // sine of the smallest angle a cut keeps from an edge
// Smallest angle (radians) a cut may make with the boundary where it ends. Without it several notches of a round
// hole all cut to the same far corner and leave a fan of slivers narrower than a bead (see the file comment). A
// piece with an angle theta at a corner gets its contour corner w/2 / sin(theta/2) from it, and the wedge in front
// is left without metal: 23 mm for a 6 mm bead at 15 degrees (the earlier limit: ~90 mm2 holes at the corners of
// planar_demo's plate), 7.8 mm at 45 degrees. Measured on the sliced scenario parts (6 layers each), 15 -> 45
// degrees took the uncovered fraction of plate_with_holes from 2.0 % to 0.7 %, ding_b 5.2 % -> 1.5 %, ding_c
// 4.9 % -> 2.2 %, for 3-15 % more path elements.
constexpr double kMinCutAngleRad = 45.0 * std::numbers::pi / 180.0;
// A vertex of the input that lies within this distance (mm) of the line through its neighbours is taken as a point
// on a straight edge, not as a corner. Sliced meshes are full of such points: a plane cuts a side facet's diagonal
// half-way along the polygon's edge, and float STL coordinates (~1e-5 mm at 100 mm) and Clipper's 1e-4 mm grid put
// it a hair off the edge, often on the inside, where it is a notch with an interior angle of pi + 1e-4 that would
// cut a disc into slivers. 1 um is far above that noise and far below anything a 3-10 mm bead can resolve.
constexpr double kStraightToleranceMm = 1e-3;

// A region being decomposed: cycles[0] is the outline (positive area, possibly weakly simple after merges), the
// others are holes (negative area). The interior is on the left of every edge.
struct WorkRegion {
  std::vector<Ring> cycles;
};

struct Vertex {
  int cycle = -1;
  int index = -1;
};

bool IsNotch(const Ring& c, int i) { return Turn(c, i) < -1e-9; }

// True if direction `u` leaves vertex i of `c` into the interior, away from both edges by kSinTolerance.
bool InWedge(const Ring& c, int i, const Vec& u) {
  const Vec e1 = (At(c, i) - At(c, i - 1)).normalized();
  const Vec e2 = (At(c, i + 1) - At(c, i)).normalized();
  const Vec un = u.normalized();
  const bool left1 = Cross(e1, un) > kSinTolerance;
  const bool left2 = Cross(e2, un) > kSinTolerance;
  return IsNotch(c, i) ? (left1 || left2) : (left1 && left2);
}

// Smaller of the two angles (radians) between direction `u` leaving vertex i and the two edges at i.
double CutAngleAt(const Ring& c, int i, const Vec& u) {
  const Vec un = u.normalized();
  const Vec to_prev = (At(c, i - 1) - At(c, i)).normalized();
  const Vec to_next = (At(c, i + 1) - At(c, i)).normalized();
  return std::min(std::acos(std::clamp(un.dot(to_prev), -1.0, 1.0)), std::acos(std::clamp(un.dot(to_next), -1.0, 1.0)));
}

// True if a cut from notch i along `w` leaves both angles at i <= pi: `w` lies in the cone between the extensions
// of the notch's two edges. The cone's sides are allowed (the angle there becomes exactly pi, e.g. a notch-notch
// cut along the common line of the two notches of a T).
bool InCone(const Ring& c, int i, const Vec& w) {
  const Vec e1 = (At(c, i) - At(c, i - 1)).normalized();
  const Vec e2 = (At(c, i + 1) - At(c, i)).normalized();
  const Vec wn = w.normalized();
  return Cross(e1, wn) >= -1e-12 && Cross(e2, wn) >= -1e-12;
}

// True if the segment p-q touches no edge of `region` other than at p and q.
bool SegmentClear(const Vec& p, const Vec& q, const WorkRegion& region, double tol) {
  const Vec d = q - p;
  const double len = d.norm();
  if (len <= tol) return false;
  const Vec u = d / len;
  auto on_open_segment = [&](const Vec& a) {
    const double t = (a - p).dot(u);
    return std::abs(Cross(u, a - p)) < tol && t > tol && t < len - tol;
  };
  for (const Ring& c : region.cycles) {
    const int n = static_cast<int>(c.size());
    for (int k = 0; k < n; ++k) {
      const Vec& a = c[k];
      const Vec& b = At(c, k + 1);
      if (on_open_segment(a) || on_open_segment(b)) return false;
      const Vec eb = b - a;
      const double el = eb.norm();
      if (el <= tol) continue;
      const double d1 = Cross(u, a - p), d2 = Cross(u, b - p);
      const double d3 = Cross(eb / el, p - a), d4 = Cross(eb / el, q - a);
      if (((d1 > tol && d2 < -tol) || (d1 < -tol && d2 > tol)) &&
          ((d3 > tol && d4 < -tol) || (d3 < -tol && d4 > tol))) {
        return false;
      }
    }
  }
  return true;
}

struct Hit {
  int cycle = -1;
  int edge = -1;  // edge from vertex `edge` to `edge + 1`
  double t = std::numeric_limits<double>::infinity();
};

// First edge of `region` that the ray p + t dir (t > 0) leaves the interior through.
Hit CastRay(const Vec& p, const Vec& dir, const WorkRegion& region, double tol) {
  Hit best;
  for (int ci = 0; ci < static_cast<int>(region.cycles.size()); ++ci) {
    const Ring& c = region.cycles[ci];
    const int n = static_cast<int>(c.size());
    for (int k = 0; k < n; ++k) {
      const Vec& a = c[k];
      const Vec& b = At(c, k + 1);
      if ((a - p).norm() < tol || (b - p).norm() < tol) continue;
      const Vec e = b - a;
      if (Cross(e, dir) >= 0.0) continue;  // the ray would enter the interior through this edge
      const double denom = Cross(dir, e);
      const double t = Cross(a - p, e) / denom;
      const double s = Cross(a - p, dir) / denom;
      if (t > tol && s >= -1e-12 && s <= 1.0 + 1e-12 && t < best.t) best = Hit{ci, k, t};
    }
  }
  return best;
}

// Builds the cycles after cutting from vertex `from` to `to` (a vertex) or to the point `h` on edge `to.index`.
std::vector<Ring> ApplyCut(const WorkRegion& region, Vertex from, Vertex to, const Vec* h) {
  std::vector<Ring> out;
  const Ring& cf = region.cycles[from.cycle];
  const int nf = static_cast<int>(cf.size());
  if (from.cycle == to.cycle) {
    // Split line: two cycles that share the cut.
    Ring a, b;
    const int j_end = to.index;
    for (int k = from.index;; k = (k + 1) % nf) {
      a.push_back(cf[k]);
      if (k == j_end) break;
    }
    if (h != nullptr) a.push_back(*h);
    const int j_start = h != nullptr ? (to.index + 1) % nf : to.index;
    if (h != nullptr) b.push_back(*h);
    for (int k = j_start;; k = (k + 1) % nf) {
      b.push_back(cf[k]);
      if (k == from.index) break;
    }
    out.push_back(std::move(a));
    out.push_back(std::move(b));
  } else {
    // Merging line: one weakly simple cycle that walks along both sides of the cut.
    const Ring& ct = region.cycles[to.cycle];
    const int nt = static_cast<int>(ct.size());
    Ring m;
    for (int k = 0; k < nf; ++k) m.push_back(cf[(from.index + k) % nf]);
    m.push_back(cf[from.index]);
    const int start = h != nullptr ? (to.index + 1) % nt : to.index;
    if (h != nullptr) m.push_back(*h);
    for (int k = 0; k < nt; ++k) m.push_back(ct[(start + k) % nt]);
    m.push_back(h != nullptr ? *h : ct[to.index]);
    out.push_back(std::move(m));
  }
  for (int ci = 0; ci < static_cast<int>(region.cycles.size()); ++ci) {
    if (ci != from.cycle && ci != to.cycle) out.push_back(region.cycles[ci]);
  }
  return out;
}

// Groups cycles into regions: positive cycles are outlines, negative ones holes of the outline that holds them.
// Returns false when a hole lies in no outline (degenerate geometry).
bool Regroup(const std::vector<Ring>& cycles, std::vector<WorkRegion>* regions_out) {
  std::vector<WorkRegion>& regions = *regions_out;
  regions.clear();
  std::vector<const Ring*> holes;
  for (const Ring& c : cycles) {
    if (SignedArea(c) > 0.0) {
      regions.push_back(WorkRegion{{c}});
    } else {
      holes.push_back(&c);
    }
  }
  for (const Ring* hole : holes) {
    int owner = -1;
    for (int r = 0; r < static_cast<int>(regions.size()) && owner < 0; ++r) {
      if (regions.size() == 1 || PointInRing(hole->front(), regions[r].cycles[0])) owner = r;
    }
    if (owner < 0) return false;
    regions[owner].cycles.push_back(*hole);
  }
  return true;
}

// Cleans a ring: drops repeated points (closer than `tol`) and vertices where the ring goes straight on, and
// orients it as asked. A vertex is dropped when it, and every point dropped before between its two neighbours, lies
// within `straight_mm` of the chord between those neighbours (so the dropped points never drift further than that
// from the ring, however many are dropped in a row). With `grow_only`, the dropped points must also lie on the
// left of the chord (the region's side when the region lies left of the ring): only notches are cut off, and the
// region can only grow.
Ring CleanRing(const Ring& in, bool ccw, double tol, double straight_mm, bool grow_only = false) {
  Ring r;
  for (const Vec& p : in) {
    if (r.empty() || (p - r.back()).norm() > tol) r.push_back(p);
  }
  while (r.size() > 1 && (r.front() - r.back()).norm() <= tol) r.pop_back();
  // dropped[k]: the points taken out between kept vertices k and k + 1.
  std::vector<std::vector<Vec>> dropped(r.size());
  for (bool changed = true; changed && r.size() > 3;) {
    changed = false;
    for (std::size_t i = 0; i < r.size() && r.size() > 3;) {
      const std::size_t n = r.size(), before = (i + n - 1) % n;
      const Vec a = r[before], c = r[(i + 1) % n];
      const double len = (c - a).norm();
      // On the chord a-c (within straight_mm of it, between its ends): a spike that turns back is never straight.
      auto on_chord = [&](const Vec& p) {
        const double t = (p - a).dot(c - a) / len;
        const double side = Cross(c - a, p - a) / len;  // > 0: left of the chord
        return t > 0.0 && t < len && std::abs(side) <= straight_mm && (!grow_only || side >= -tol);
      };
      bool straight = len > tol && on_chord(r[i]);
      for (const Vec& p : dropped[before]) straight = straight && on_chord(p);
      for (const Vec& p : dropped[i]) straight = straight && on_chord(p);
      if (!straight) {
        ++i;
        continue;
      }
      dropped[before].push_back(r[i]);
      dropped[before].insert(dropped[before].end(), dropped[i].begin(), dropped[i].end());
      r.erase(r.begin() + static_cast<std::ptrdiff_t>(i));
      dropped.erase(dropped.begin() + static_cast<std::ptrdiff_t>(i));
      changed = true;
    }
  }
  if ((SignedArea(r) > 0.0) != ccw) std::reverse(r.begin(), r.end());
  return r;
}

// What EliminateOneNotch did.
enum class NotchStep { kNoNotchLeft, kCut, kNoUsableCut };

// The notch with the greatest interior angle (Ding eq. (1)-(2)); cycle -1 when the region is convex.
Vertex WidestNotch(const WorkRegion& region) {
  Vertex ref;
  double best_phi = std::numbers::pi + 1e-9;
  for (int ci = 0; ci < static_cast<int>(region.cycles.size()); ++ci) {
    for (int i = 0; i < static_cast<int>(region.cycles[ci].size()); ++i) {
      const double phi = std::numbers::pi - Turn(region.cycles[ci], i);  // interior angle
      if (phi > best_phi) {
        best_phi = phi;
        ref = Vertex{ci, i};
      }
    }
  }
  return ref;
}

// Scan zone of notch `ref` (at p, its edges' extensions r1 and r2, bisector between them): the visible vertices
// strictly inside the cone between r1 and r2 (see the file comment) that can take the cut, nearest the bisector
// line: the best notch and the best other vertex (cycle -1 where there is none).
void ScanZone(const WorkRegion& region, const Vertex& ref, const Vec& bisector, double tol, Vertex* best_notch,
              Vertex* best_vertex) {
  const Ring& c = region.cycles[ref.cycle];
  const Vec p = c[ref.index];
  double notch_dist = std::numeric_limits<double>::infinity(), vertex_dist = notch_dist;
  for (int cj = 0; cj < static_cast<int>(region.cycles.size()); ++cj) {
    const Ring& cc = region.cycles[cj];
    for (int j = 0; j < static_cast<int>(cc.size()); ++j) {
      const Vec w = cc[j] - p;
      if (w.norm() <= tol) continue;
      if (!InCone(c, ref.index, w) || !InWedge(cc, j, -w)) continue;
      if (CutAngleAt(cc, j, -w) < kMinCutAngleRad || !SegmentClear(p, cc[j], region, tol)) continue;
      const double dist = std::abs(Cross(bisector, w));  // distance to the bisector line
      if (IsNotch(cc, j)) {
        if (dist < notch_dist) notch_dist = dist, *best_notch = Vertex{cj, j};
      } else if (dist < vertex_dist) {
        vertex_dist = dist, *best_vertex = Vertex{cj, j};
      }
    }
  }
}

// A notch-line cut: to a vertex, or to the point h on an edge (`on_edge`, the edge's first vertex as target), and
// the angle it makes there (rad; -1: none found).
struct NotchLineCut {
  Vertex target;
  Vec h;
  bool on_edge = false;
  double angle = -1.0;
};

// Notch-line routine from p (its edges' extensions r1 and r2): the bisector to the first edge. If it lands on a
// vertex that cannot take the cut, or meets the edge at a grazing angle (a sliver), tilt it inside the cone; the
// steepest usable direction wins.
NotchLineCut BestLineCut(const WorkRegion& region, const Vec& p, const Vec& r1, const Vec& r2, double tol) {
  NotchLineCut best_line;
  for (double alpha : {0.5, 0.4, 0.6, 0.3, 0.7, 0.2, 0.8, 0.1, 0.9}) {
    const Vec dir = (alpha * r1 + (1.0 - alpha) * r2).normalized();
    const Hit hit = CastRay(p, dir, region, tol);
    if (hit.cycle < 0) continue;
    const Ring& hc = region.cycles[hit.cycle];
    const Vec h = p + hit.t * dir;
    const int n = static_cast<int>(hc.size());
    NotchLineCut cut{Vertex{hit.cycle, hit.edge}, h, true, 0.0};
    for (int end : {hit.edge, (hit.edge + 1) % n}) {
      if (cut.on_edge && (h - hc[end]).norm() <= 1e3 * tol) {
        cut = NotchLineCut{Vertex{hit.cycle, end}, hc[end], false, 0.0};
      }
    }
    if (cut.on_edge) {
      const Vec e = (At(hc, hit.edge + 1) - hc[hit.edge]).normalized();
      cut.angle = std::min(std::acos(std::clamp(e.dot(-dir), -1.0, 1.0)), std::acos(std::clamp(e.dot(dir), -1.0, 1.0)));
    } else if (InWedge(hc, cut.target.index, p - hc[cut.target.index]) &&
               SegmentClear(p, hc[cut.target.index], region, tol)) {
      cut.angle = CutAngleAt(hc, cut.target.index, p - hc[cut.target.index]);
    } else {
      continue;
    }
    if (cut.angle > best_line.angle) best_line = cut;
    if (best_line.angle >= kMinCutAngleRad) break;
  }
  return best_line;
}

// Chooses and applies the cut that removes the notch with the greatest interior angle: to the notch nearest its
// bisector in its scan zone (notch-notch), else the nearest vertex (notch-vertex), else along a line (notch-line).
// Returns kNoNotchLeft if the region is convex, kNoUsableCut if degenerate geometry leaves the notch without a usable
// cut.
NotchStep EliminateOneNotch(const WorkRegion& region, double tol, std::vector<Ring>* cycles_out) {
  const Vertex ref = WidestNotch(region);
  if (ref.cycle < 0) return NotchStep::kNoNotchLeft;
  const Ring& c = region.cycles[ref.cycle];
  const Vec p = c[ref.index];
  const Vec r1 = (p - At(c, ref.index - 1)).normalized();  // extension of V_{i-1} V_i
  const Vec r2 = (p - At(c, ref.index + 1)).normalized();  // extension of V_{i+1} V_i
  const Vec bisector = (r1 + r2).normalized();
  Vertex best_notch, best_vertex;
  ScanZone(region, ref, bisector, tol, &best_notch, &best_vertex);
  if (best_notch.cycle >= 0) {  // notch-notch routine
    *cycles_out = ApplyCut(region, ref, best_notch, nullptr);
    return NotchStep::kCut;
  }
  if (best_vertex.cycle >= 0) {  // notch-vertex routine
    *cycles_out = ApplyCut(region, ref, best_vertex, nullptr);
    return NotchStep::kCut;
  }
  const NotchLineCut best_line = BestLineCut(region, p, r1, r2, tol);
  if (best_line.angle >= 0.0) {
    *cycles_out = best_line.on_edge ? ApplyCut(region, ref, best_line.target, &best_line.h)
                                    : ApplyCut(region, ref, best_line.target, nullptr);
    return NotchStep::kCut;
  }
  return NotchStep::kNoUsableCut;
}

// Inserts into each piece the vertices of other pieces that lie inside its edges, so that neighbours share edges
// vertex for vertex (a cut that ended on an earlier cut splits that cut's edge on one side only).
void ResolveTJunctions(std::vector<Ring>* pieces, double tol) {
  for (Ring& piece : *pieces) {
    for (int k = 0; k < static_cast<int>(piece.size()); ++k) {
      const Vec a = piece[k], b = At(piece, k + 1);
      const double len = (b - a).norm();
      if (len <= tol) continue;
      const Vec u = (b - a) / len;
      double best_t = len;
      Vec best = Vec::Zero();
      for (const Ring& other : *pieces) {
        for (const Vec& v : other) {
          const double t = (v - a).dot(u);
          if (t > 1e3 * tol && t < best_t - 1e3 * tol && std::abs(Cross(u, v - a)) < 1e3 * tol) best_t = t, best = v;
        }
      }
      if (best_t < len) piece.insert(piece.begin() + k + 1, best);
    }
  }
}

// Removes cuts that are not needed: two pieces that share a whole edge and whose union is convex become one piece
// (Hertel-Mehlhorn). Thin pieces are merged first, since a piece narrower than a bead gets no path of its own.
void MergeConvexNeighbours(std::vector<Ring>* pieces, double tol) {
  ResolveTJunctions(pieces, tol);
  while (true) {
    int best_i = -1, best_j = -1;
    Ring best_union;
    double best_width = std::numeric_limits<double>::infinity();
    for (int i = 0; i < static_cast<int>(pieces->size()); ++i) {
      const Ring& a = (*pieces)[i];
      for (int j = 0; j < static_cast<int>(pieces->size()); ++j) {
        const Ring& b = (*pieces)[j];
        if (i == j) continue;
        for (int ka = 0; ka < static_cast<int>(a.size()); ++ka) {
          const Vec p = a[ka], q = At(a, ka + 1);
          int kb = -1;
          for (int k = 0; k < static_cast<int>(b.size()) && kb < 0; ++k) {
            if ((b[k] - q).norm() < 1e3 * tol && (At(b, k + 1) - p).norm() < 1e3 * tol) kb = k;
          }
          if (kb < 0) continue;
          // Union: a from q round to p, then b from p (exclusive) round to q (exclusive).
          Ring u;
          for (int k = 1; k <= static_cast<int>(a.size()); ++k) u.push_back(At(a, ka + k));
          for (int k = 2; k < static_cast<int>(b.size()); ++k) u.push_back(At(b, kb + k));
          if (!IsConvex(u, 1e-9)) continue;
          double wa = 0.0, wb = 0.0;  // a piece too thin to have a width counts as width 0
          if (ConvexHull(a).size() >= 3) MinimumWidthDirection(a, &wa);
          if (ConvexHull(b).size() >= 3) MinimumWidthDirection(b, &wb);
          if (std::min(wa, wb) < best_width) best_width = std::min(wa, wb), best_i = i, best_j = j, best_union = u;
        }
      }
    }
    if (best_i < 0) return;
    (*pieces)[best_i] = CleanRing(best_union, true, tol, tol);
    pieces->erase(pieces->begin() + best_j);
  }
}

}  // namespace

Ring FillShallowNotches(const Ring& ring, double depth_mm) {
  WAAM_THROW_UNLESS(depth_mm >= 0.0, "notch filling: depth " << depth_mm << " mm: must be >= 0");
  if (ring.size() < 4) return ring;
  const double tol = 1e-9 * std::max(1.0, BoundingDiagonal(PolygonWithHoles{ring, {}}));
  return CleanRing(ring, SignedArea(ring) > 0.0, tol, std::max(depth_mm, tol), /*grow_only=*/true);
}

ConvexDecomposition DecomposeConvex(const PolygonWithHoles& region) {
  const double scale = std::max(1.0, BoundingDiagonal(region));
  const double tol = 1e-9 * scale;
  WorkRegion start;
  start.cycles.push_back(CleanRing(region.outer, true, tol, kStraightToleranceMm));
  WAAM_THROW_UNLESS(start.cycles[0].size() >= 3 && SignedArea(start.cycles[0]) > tol,
                    "convex decomposition: region outline has " << start.cycles[0].size()
                                                                << " distinct vertices and no area: need >= 3");
  for (const Ring& hole : region.holes) {
    Ring h = CleanRing(hole, false, tol, kStraightToleranceMm);
    if (h.size() >= 3 && std::abs(SignedArea(h)) > tol) start.cycles.push_back(std::move(h));
  }
  std::size_t budget = 16;
  for (const Ring& c : start.cycles) budget += 2 * c.size();

  ConvexDecomposition out;
  std::vector<WorkRegion> stack{start};
  std::vector<WorkRegion> regrouped;
  while (!stack.empty()) {
    WorkRegion current = std::move(stack.back());
    stack.pop_back();
    std::vector<Ring> cycles;
    const NotchStep step = EliminateOneNotch(current, tol, &cycles);
    if (step == NotchStep::kNoNotchLeft) {
      out.pieces.push_back(CleanRing(current.cycles[0], true, tol, tol));
      continue;
    }
    if (step == NotchStep::kNoUsableCut) out.failure = "no usable cut for a notch";
    if (out.ok() && --budget == 0) out.failure = "too many cuts";
    if (out.ok() && !Regroup(cycles, &regrouped)) out.failure = "a cut left a hole outside every outline";
    if (!out.ok()) {
      out.pieces.clear();
      return out;
    }
    for (WorkRegion& r : regrouped) stack.push_back(std::move(r));
  }
  MergeConvexNeighbours(&out.pieces, tol);
  return out;
}

}  // namespace waam::planner
