// Uncovered slice area: the slice minus the weld moves buffered by half their bead width, in the slice plane,
// measured column by column.
#include "planner/path/coverage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "planner/geometry/bead_outline.h"
#include "planner/geometry/clipper_adapter.h"
#include "planner/geometry/polygon.h"

namespace waam::planner {
namespace {

// Moves are grouped by bead width in bins this wide (a CSW plan varies it point by point), each group buffered at once.
constexpr double kWidthBinMm = 0.05;
// Chord tolerance (mm) of the beads' round ends and joins: a chord cuts a little of the disc off, and a pass
// buffered as one polyline has fewer ends to make up for it than its moves buffered one by one.
constexpr double kCoverageArcToleranceMm = 0.01;
// Columns are this many (largest) bead widths wide, at most kMaxColumns of them.
constexpr double kColumnBeadWidths = 8.0;
constexpr int kMaxColumns = 256;

// One weld move in the slice plane with its bead.
struct Bead {
  Eigen::Vector2d a, b;
  long width_bin;    // bead width in kWidthBinMm
  double radius_mm;  // half that width
  bool continues;    // the move before it is a weld move of the same bead width that ends at a
};

// The part of segment a-b with lo <= x <= hi, keeping its direction; false when none. `*cut_a`, `*cut_b`: whether
// that end moved.
bool ClipToSlab(Eigen::Vector2d* a, Eigen::Vector2d* b, double lo, double hi, bool* cut_a, bool* cut_b) {
  *cut_a = *cut_b = false;
  if (std::max(a->x(), b->x()) < lo || std::min(a->x(), b->x()) > hi) return false;
  const Eigen::Vector2d a0 = *a, d = *b - *a;
  auto at_x = [&](double x) { return Eigen::Vector2d(a0 + d * ((x - a0.x()) / d.x())); };
  if (a->x() < lo) *a = at_x(lo), *cut_a = true;
  if (a->x() > hi) *a = at_x(hi), *cut_a = true;
  if (b->x() < lo) *b = at_x(lo), *cut_b = true;
  if (b->x() > hi) *b = at_x(hi), *cut_b = true;
  return true;
}

// The part of a Clipper ring with lo <= x <= hi (Clipper units), by Sutherland-Hodgman against the slab's two sides:
// the same orientation, and where the ring leaves and re-enters the slab, an edge along its side; such edges of
// one ring overlap with opposite directions and cancel under the non-zero rule. Empty when nothing is left.
ClipperLib::Path CutRingToSlab(const ClipperLib::Path& ring, ClipperLib::cInt lo, ClipperLib::cInt hi) {
  auto cut = [](const ClipperLib::Path& in, ClipperLib::cInt x0, bool keep_above) {
    ClipperLib::Path out;
    if (in.empty()) return out;
    auto inside = [&](const ClipperLib::IntPoint& p) { return keep_above ? p.X >= x0 : p.X <= x0; };
    auto crossing = [&](const ClipperLib::IntPoint& s, const ClipperLib::IntPoint& e) {
      const double t = static_cast<double>(x0 - s.X) / static_cast<double>(e.X - s.X);
      return ClipperLib::IntPoint(x0, s.Y + static_cast<ClipperLib::cInt>(std::llround(t * static_cast<double>(e.Y - s.Y))));
    };
    ClipperLib::IntPoint s = in.back();
    for (const ClipperLib::IntPoint& e : in) {
      if (inside(e)) {
        if (!inside(s)) out.push_back(crossing(s, e));
        out.push_back(e);
      } else if (inside(s)) {
        out.push_back(crossing(s, e));
      }
      s = e;
    }
    return out;
  };
  ClipperLib::Path out = cut(cut(ring, lo, true), hi, false);
  if (out.size() < 3) out.clear();
  return out;
}

// Every ring of `paths` cut to lo <= x <= hi (mm), rings wholly inside kept as they are.
ClipperLib::Paths CutToSlab(const ClipperLib::Paths& paths, double lo_mm, double hi_mm) {
  const ClipperLib::cInt lo = internal::ToClipper({lo_mm, 0.0}).X, hi = internal::ToClipper({hi_mm, 0.0}).X;
  ClipperLib::Paths out;
  for (const ClipperLib::Path& ring : paths) {
    ClipperLib::cInt ring_lo = ring.front().X, ring_hi = ring_lo;
    for (const ClipperLib::IntPoint& p : ring) ring_lo = std::min(ring_lo, p.X), ring_hi = std::max(ring_hi, p.X);
    if (ring_hi < lo || ring_lo > hi) continue;
    if (ring_lo >= lo && ring_hi <= hi) {
      out.push_back(ring);
      continue;
    }
    ClipperLib::Path cut = CutRingToSlab(ring, lo, hi);
    if (!cut.empty()) out.push_back(std::move(cut));
  }
  return out;
}

}  // namespace

double UncoveredArea(const LayerPath& layer) {
  if (!layer.slice_in_plane) return std::numeric_limits<double>::quiet_NaN();
  if (layer.slice.empty()) return 0.0;
  std::vector<Bead> beads;
  double radius_max = 0.0;
  for (std::size_t i = 1; i < layer.points.size(); ++i) {
    const PathPoint& p = layer.points[i];
    if (!p.weld || p.bead_width_mm <= 0.0) continue;
    const Eigen::Vector2d a = layer.slice_axes_P.transpose() * (layer.points[i - 1].p_P - layer.slice_origin_P);
    const Eigen::Vector2d b = layer.slice_axes_P.transpose() * (p.p_P - layer.slice_origin_P);
    const long bin = std::lround(p.bead_width_mm / kWidthBinMm);
    const double radius = 0.5 * bin * kWidthBinMm;
    const bool continues = !beads.empty() && beads.back().width_bin == bin && beads.back().b == a;
    beads.push_back({a, b, bin, radius, continues});
    radius_max = std::max(radius_max, radius);
  }
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  for (const PolygonWithHoles& region : layer.slice) {
    for (const Eigen::Vector2d& p : region.outer) {
      x_lo = std::min(x_lo, p.x()), x_hi = std::max(x_hi, p.x());
    }
  }
  if (!(x_hi > x_lo)) return Area(layer.slice);
  // One Clipper union of every bead of a layer holds, at each sweep line, every bead edge the line crosses: with K
  // nested contour rings that is O(K) edges at each of O(K N) vertices, O(K^2 N) in all. Cut in columns a few
  // beads wide, each sweep line crosses O(1) beads. The columns partition the slice, so their areas add up; a
  // bead point within a bead radius of a column's sides can cover it, so beads are clipped to the column widened
  // by that radius (exact: the discs centred outside reach nothing inside).
  const int columns = beads.empty() ? 1
                                    : std::clamp(static_cast<int>(std::ceil((x_hi - x_lo) /
                                                                            (kColumnBeadWidths * 2.0 * radius_max))),
                                                 1, kMaxColumns);
  const double column_mm = (x_hi - x_lo) / columns;
  const ClipperLib::Paths slice_paths = internal::ToPaths(layer.slice);
  double uncovered = 0.0;
  for (int c = 0; c < columns; ++c) {
    // The first and last column reach past the slice, so no sliver of it is missed by rounding.
    const double lo = c == 0 ? x_lo - 1.0 : x_lo + c * column_mm;
    const double hi = c == columns - 1 ? x_hi + 1.0 : x_lo + (c + 1) * column_mm;
    const ClipperLib::Paths part = columns == 1 ? slice_paths : CutToSlab(slice_paths, lo, hi);
    if (part.empty()) continue;
    // Each pass as one polyline (the buffer of a polyline is the union of its moves' buffers, and Clipper's union
    // of a polyline's buffer meets far fewer crossings than that of separate moves), cut where it leaves the column.
    std::map<long, std::vector<internal::Polyline>> by_width;
    internal::Polyline* open = nullptr;  // the polyline the next move may extend
    for (const Bead& bead : beads) {
      Eigen::Vector2d a = bead.a, b = bead.b;
      bool cut_a = false, cut_b = false;
      if (!ClipToSlab(&a, &b, lo - bead.radius_mm, hi + bead.radius_mm, &cut_a, &cut_b)) {
        open = nullptr;
        continue;
      }
      if (open != nullptr && bead.continues && !cut_a) {
        open->push_back(b);
      } else {
        std::vector<internal::Polyline>& lines = by_width[bead.width_bin];
        lines.push_back({a, b});
        open = &lines.back();
      }
      if (cut_b) open = nullptr;
    }
    // The beads' outlines of every width, their union and the difference in one Clipper pass.
    ClipperLib::Paths outlines;
    for (const auto& [bin, moves] : by_width) {
      internal::AppendBeadOutlines(moves, 0.5 * bin * kWidthBinMm, kCoverageArcToleranceMm, &outlines);
    }
    uncovered += internal::AreaOutsideBeads(part, outlines);
  }
  return uncovered;
}

}  // namespace waam::planner
