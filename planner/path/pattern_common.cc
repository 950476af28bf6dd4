// Option checks, start points, rasters and move-list helpers shared by the layer patterns.
#include "planner/path/pattern_common.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <tuple>

#include "models/core/error.h"
#include "planner/geometry/convex_decomposition.h"

namespace waam::planner::internal {
namespace {

using Vec = Eigen::Vector2d;

// First and last raster line sit this far (mm) inside the extremes of the area, so Clipper never clips a line
// that runs exactly along a flush edge.
constexpr double kRasterInsetMm = 1e-3;

}  // namespace

void ValidatePatternOptions(const PatternOptions& options) {
  WAAM_THROW_UNLESS(options.pattern != Pattern::kSpiral, "path pattern 'spiral': needs slicing.type skeleton");
  WAAM_THROW_UNLESS(std::isfinite(options.bead_width_mm) && options.bead_width_mm > 0.0,
                    "path bead_width_mm = " << options.bead_width_mm << ": must be > 0");
  WAAM_THROW_UNLESS(std::isfinite(options.zigzag_angle_rad),
                    "path zigzag_angle = " << options.zigzag_angle_rad << " rad: must be finite");
  WAAM_THROW_UNLESS(std::isfinite(options.contour_tolerance_mm) && options.contour_tolerance_mm >= 0.0,
                    "path contour_tolerance_mm = " << options.contour_tolerance_mm << ": must be >= 0");
  WAAM_THROW_UNLESS(options.layer_index >= 0, "path layer_index = " << options.layer_index << ": must be >= 0");
}

double LinkSlackMm(const PatternOptions& options) { return 0.01 + options.contour_tolerance_mm; }

double StartFraction(const PatternOptions& options) {
  if (!options.alternate_start) return 0.0;
  std::mt19937_64 rng(options.seed);
  const double offset = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
  const double f = offset + options.layer_index * (std::numbers::phi - 1.0);
  return f - std::floor(f);
}

Eigen::Vector2d PointAlongRing(const Ring& ring, double fraction) {
  const double target = Perimeter(ring) * fraction;
  double walked = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec& a = ring[i];
    const Vec& b = ring[(i + 1) % ring.size()];
    const double len = (b - a).norm();
    if (walked + len >= target && len > 0.0) return a + (b - a) * ((target - walked) / len);
    walked += len;
  }
  return ring.front();
}

void AppendLoop(const Ring& loop, const Eigen::Vector2d& start_near, bool reverse, std::vector<Move2D>* moves) {
  const std::size_t n = loop.size();
  if (n < 2) return;
  // Nearest point of the loop to start_near: edge index and the point on it.
  std::size_t best_edge = 0;
  Vec best_point = loop[0];
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec& a = loop[i];
    const Vec& b = loop[(i + 1) % n];
    const double l2 = (b - a).squaredNorm();
    const double t = l2 > 0.0 ? std::clamp((start_near - a).dot(b - a) / l2, 0.0, 1.0) : 0.0;
    const Vec q = a + t * (b - a);
    if ((q - start_near).norm() < best) best = (q - start_near).norm(), best_edge = i, best_point = q;
  }
  std::vector<Vec> order{best_point};
  for (std::size_t k = 1; k <= n; ++k) order.push_back(loop[(best_edge + k) % n]);
  order.push_back(best_point);
  if (reverse) std::reverse(order.begin(), order.end());
  moves->push_back(Move2D{order.front(), false});
  for (std::size_t k = 1; k < order.size(); ++k) {
    if ((order[k] - moves->back().p).norm() > 1e-9) moves->push_back(Move2D{order[k], true});
  }
}

std::vector<Move2D> SimplifyMoves(const std::vector<Move2D>& moves, double tolerance_mm) {
  std::vector<Move2D> out;
  std::vector<Vec> dropped;  // points merged away inside the last weld move of `out`
  for (const Move2D& move : moves) {
    if (move.weld && out.size() >= 2 && out.back().weld) {
      // Try to extend the last weld move a -> b to a -> c, dropping b.
      const Vec a = out[out.size() - 2].p, b = out.back().p, c = move.p;
      const double len = (c - a).norm();
      auto near_chord = [&](const Vec& q) {
        const double t = (q - a).dot(c - a) / len;
        return t > 0.0 && t < len && std::abs((c - a).x() * (q - a).y() - (c - a).y() * (q - a).x()) / len <= tolerance_mm;
      };
      bool straight = len > 1e-9 && near_chord(b);
      for (const Vec& q : dropped) straight = straight && near_chord(q);
      if (straight) {
        dropped.push_back(b);
        out.back().p = c;
        continue;
      }
    }
    out.push_back(move);
    dropped.clear();
  }
  return out;
}

std::vector<Move2D> ReverseMoves(const std::vector<Move2D>& moves) {
  std::vector<Move2D> out(moves.rbegin(), moves.rend());
  for (std::size_t k = 0; k < out.size(); ++k) {
    // The move ending at out[k] is the old move that started there, i.e. the old successor's flag.
    out[k].weld = k == 0 ? false : moves[moves.size() - k].weld;
  }
  return out;
}

double RasterAngle(const PolygonWithHoles& region, const PatternOptions& options) {
  if (!options.zigzag_auto) return options.zigzag_angle_rad;
  const Ring hull = ConvexHull(region.outer);
  if (hull.size() < 3) return 0.0;
  return MinimumWidthDirection(hull, nullptr);
}

std::vector<RasterSegment> RasterFill(const std::vector<PolygonWithHoles>& area, double angle_rad,
                                      double spacing_mm) {
  const Vec u(std::cos(angle_rad), std::sin(angle_rad));
  const Vec n(-u.y(), u.x());
  double n_min = std::numeric_limits<double>::infinity(), n_max = -n_min;
  double x_min = n_min, x_max = -n_min;
  for (const PolygonWithHoles& region : area) {
    for (const Vec& p : region.outer) {
      n_min = std::min(n_min, n.dot(p)), n_max = std::max(n_max, n.dot(p));
      x_min = std::min(x_min, u.dot(p)), x_max = std::max(x_max, u.dot(p));
    }
  }
  std::vector<RasterSegment> out;
  if (!(n_max > n_min)) return out;
  const double span = std::max(0.0, n_max - n_min - 2.0 * kRasterInsetMm);
  const int lines = static_cast<int>(std::ceil(span / spacing_mm - 1e-9)) + 1;
  const double step = lines > 1 ? span / (lines - 1) : 0.0;
  const double first = lines > 1 ? n_min + kRasterInsetMm : 0.5 * (n_min + n_max);
  std::vector<Polyline> raw;
  for (int k = 0; k < lines; ++k) {
    const double level = first + k * step;
    raw.push_back({u * (x_min - 1.0) + n * level, u * (x_max + 1.0) + n * level});
  }
  for (const Polyline& piece : ClipPolylines(raw, area)) {
    Vec a = piece.front(), b = piece.back();
    if ((b - a).norm() < 1e-6) continue;
    if (u.dot(b - a) < 0.0) std::swap(a, b);
    const int line = step > 0.0 ? static_cast<int>(std::lround((n.dot(a) - first) / step)) : 0;
    out.push_back(RasterSegment{a, b, line});
  }
  std::sort(out.begin(), out.end(), [&](const RasterSegment& s, const RasterSegment& t) {
    return s.line != t.line ? s.line < t.line : u.dot(s.a) < u.dot(t.a);
  });
  return out;
}

bool SegmentInside(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::vector<PolygonWithHoles>& area) {
  const double length = (b - a).norm();
  if (length < 1e-9) return true;
  double inside = 0.0;
  for (const Polyline& piece : ClipPolylines({{a, b}}, area)) inside += Length(piece);
  return inside >= length - 1e-3;
}

void LinkRasters(std::vector<RasterSegment> segments, const std::vector<PolygonWithHoles>& link_area,
                 double max_link_mm, std::vector<Move2D>* moves) {
  std::vector<bool> used(segments.size(), false);
  std::size_t remaining = segments.size();
  bool have_current = false;
  Vec current = Vec::Zero();
  int current_line = 0;
  while (remaining > 0) {
    // Unvisited segment ends on a neighbouring line, nearest first: the first one with a usable link is welded to.
    int best = -1;
    bool best_flip = false;
    bool linked = false;
    if (have_current) {
      std::vector<std::tuple<double, int, bool>> near;
      for (std::size_t i = 0; i < segments.size(); ++i) {
        if (used[i] || std::abs(segments[i].line - current_line) != 1) continue;
        for (bool flip : {false, true}) {
          const double d = ((flip ? segments[i].b : segments[i].a) - current).norm();
          if (d <= max_link_mm) near.emplace_back(d, static_cast<int>(i), flip);
        }
      }
      std::sort(near.begin(), near.end());
      for (const auto& [d, i, flip] : near) {
        if (SegmentInside(current, flip ? segments[i].b : segments[i].a, link_area)) {
          best = i, best_flip = flip, linked = true;
          break;
        }
      }
    }
    // Otherwise travel (arc off) to the nearest unvisited segment end anywhere.
    if (!linked) {
      double best_d = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < segments.size(); ++i) {
        if (used[i]) continue;
        for (bool flip : {false, true}) {
          const double d = have_current ? ((flip ? segments[i].b : segments[i].a) - current).norm() : 0.0;
          if (d < best_d) best_d = d, best = static_cast<int>(i), best_flip = flip;
        }
      }
    }
    const RasterSegment& s = segments[best];
    const Vec from = best_flip ? s.b : s.a;
    const Vec to = best_flip ? s.a : s.b;
    moves->push_back(Move2D{from, linked});
    moves->push_back(Move2D{to, true});
    used[best] = true;
    --remaining;
    have_current = true;
    current = to;
    current_line = s.line;
  }
}

}  // namespace waam::planner::internal
