// Retract, travel and approach between passes: the welded TCP segments kept in a uniform grid for clearance queries.
#include "planner/path/retract.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace waam::planner {
namespace {

using Eigen::Vector3d;

constexpr double kInf = std::numeric_limits<double>::infinity();
// A travel may come this share of the clearance closer to the metal: the chords between the lifted points of a
// densified travel along a curved layer dip by step^2 / 8 R (2 mm steps on a 60 mm cone: 0.01 mm).
constexpr double kSlack = 0.01;

// The TCP segments welded so far, cut into pieces no longer than a cell and listed in every cell their bounding
// box touches.
class WeldedGrid {
 public:
  explicit WeldedGrid(double cell_mm) : cell_(cell_mm) {}

  void Add(const Vector3d& a, const Vector3d& b) {
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / cell_)));
    for (int k = 0; k < n; ++k) {
      const Vector3d p0 = a + (b - a) * (static_cast<double>(k) / n);
      const Vector3d p1 = a + (b - a) * (static_cast<double>(k + 1) / n);
      const int id = static_cast<int>(pieces_.size());
      pieces_.emplace_back(p0, p1);
      ForCells(p0.cwiseMin(p1), p0.cwiseMax(p1), [&](std::uint64_t key) { cells_[key].push_back(id); });
    }
    lo_ = lo_.cwiseMin(a.cwiseMin(b));
    hi_ = hi_.cwiseMax(a.cwiseMax(b));
  }

  // Whether the segment p-q comes closer than `limit_mm` to a welded piece.
  bool Closer(const Vector3d& p, const Vector3d& q, double limit_mm) {
    if (pieces_.empty()) return false;
    ++stamp_;
    stamps_.resize(pieces_.size(), 0);
    const int n = std::max(1, static_cast<int>(std::ceil((q - p).norm() / cell_)));
    for (int k = 0; k < n; ++k) {
      const Vector3d p0 = p + (q - p) * (static_cast<double>(k) / n);
      const Vector3d p1 = p + (q - p) * (static_cast<double>(k + 1) / n);
      const Vector3d grow = Vector3d::Constant(limit_mm);
      bool hit = false;
      ForCells(p0.cwiseMin(p1) - grow, p0.cwiseMax(p1) + grow, [&](std::uint64_t key) {
        if (hit) return;
        const auto it = cells_.find(key);
        if (it == cells_.end()) return;
        for (const int id : it->second) {
          if (stamps_[id] == stamp_) continue;
          stamps_[id] = stamp_;
          if (internal::SegmentDistance(p0, p1, pieces_[id].first, pieces_[id].second) < limit_mm) {
            hit = true;
            return;
          }
        }
      });
      if (hit) return true;
    }
    return false;
  }

  bool empty() const { return pieces_.empty(); }
  const Vector3d& lo() const { return lo_; }
  const Vector3d& hi() const { return hi_; }

 private:
  template <typename F>
  void ForCells(const Vector3d& lo, const Vector3d& hi, F&& f) const {
    const Eigen::Vector3i a = (lo / cell_).array().floor().cast<int>();
    const Eigen::Vector3i b = (hi / cell_).array().floor().cast<int>();
    for (int x = a.x(); x <= b.x(); ++x) {
      for (int y = a.y(); y <= b.y(); ++y) {
        for (int z = a.z(); z <= b.z(); ++z) f(Key(x, y, z));
      }
    }
  }
  static std::uint64_t Key(int x, int y, int z) {
    constexpr std::int64_t kOffset = 1 << 20;
    return (static_cast<std::uint64_t>(x + kOffset) << 42) | (static_cast<std::uint64_t>(y + kOffset) << 21) |
           static_cast<std::uint64_t>(z + kOffset);
  }

  double cell_;
  std::vector<std::pair<Vector3d, Vector3d>> pieces_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
  std::vector<std::uint32_t> stamps_;
  std::uint32_t stamp_ = 0;
  Vector3d lo_ = Vector3d::Constant(kInf);
  Vector3d hi_ = Vector3d::Constant(-kInf);
};

// Where the ray from x along the unit direction t leaves the box [lo, hi] (x itself when it is not inside). The
// bottom face is left out: the plate lies under it, so a ray is never sent out through it.
Vector3d LeaveBox(const Vector3d& x, const Vector3d& t, const Vector3d& lo, const Vector3d& hi) {
  if ((x.array() <= lo.array()).any() || (x.array() >= hi.array()).any()) return x;
  double s = kInf;
  for (int k = 0; k < 3; ++k) {
    if (t[k] > 1e-12) s = std::min(s, (hi[k] - x[k]) / t[k]);
    if (t[k] < -1e-12 && k < 2) s = std::min(s, (lo[k] - x[k]) / t[k]);
  }
  return std::isfinite(s) ? Vector3d(x + s * t) : x;
}

PathPoint TravelPoint(const PathPoint& like, const Vector3d& p_P, const Vector3d& tool_dir_P) {
  PathPoint p = like;
  p.p_P = p_P;
  p.tool_dir_P = tool_dir_P;
  p.weld = false;
  return p;
}

// The rebuilt path: appends a point to its layer, leaving out an arc-off point where the path already is.
class PathOut {
 public:
  explicit PathOut(std::size_t layers) : layers_(layers) {}
  void Push(std::size_t layer, const PathPoint& p) {
    if (have_last_ && !p.weld && (last_ - p.p_P).norm() < 1e-9) return;
    layers_[layer].push_back(p);
    last_ = p.p_P;
    have_last_ = true;
  }
  std::vector<PathPoint>& layer(std::size_t l) { return layers_[l]; }

 private:
  std::vector<std::vector<PathPoint>> layers_;
  Vector3d last_ = Vector3d::Zero();
  bool have_last_ = false;
};

}  // namespace

namespace internal {

// Closest points of two segments (Ericson, Real-Time Collision Detection, sec. 5.1.9).
double SegmentDistance(const Vector3d& a0, const Vector3d& a1, const Vector3d& b0, const Vector3d& b1) {
  const Vector3d d1 = a1 - a0, d2 = b1 - b0, r = a0 - b0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kEps = 1e-18;
  double s = 0.0, t = 0.0;
  if (a <= kEps && e <= kEps) return r.norm();
  if (a <= kEps) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kEps) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > kEps ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((a0 + s * d1) - (b0 + t * d2)).norm();
}

double DistanceToWelded(const Plan& plan, std::size_t layer, std::size_t before, const Vector3d& p,
                        const Vector3d& q, double limit_mm) {
  double best = limit_mm;
  const PathPoint* prev = nullptr;
  for (std::size_t l = 0; l <= layer && l < plan.layers.size(); ++l) {
    const std::vector<PathPoint>& points = plan.layers[l].points;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (l == layer && i >= before) return best;
      if (prev != nullptr && points[i].weld) {
        best = std::min(best, SegmentDistance(p, q, prev->p_P, points[i].p_P));
      }
      prev = &points[i];
    }
  }
  return best;
}

}  // namespace internal

namespace {

// Travel points, each with its layer.
using Route = std::vector<std::pair<std::size_t, PathPoint>>;

// `p` moved `r` mm up its torch axis, as a travel point.
PathPoint Lifted(const PathPoint& p, double r) { return TravelPoint(p, p.p_P + r * p.tool_dir_P, p.tool_dir_P); }

// Where the previous pass ended: its last weld point A and the lift L = A + r t_A above it, in layer `layer`.
struct PassEnd {
  PathPoint end;
  PathPoint lift;
  std::size_t layer = 0;
  bool any = false;  // false before the first pass
};

// True when the route from `from` keeps `limit_mm` from every welded segment.
bool RouteClear(WeldedGrid& welded, Vector3d from, const Route& route, double limit_mm) {
  for (const auto& [layer, q] : route) {
    if (welded.Closer(from, q.p_P, limit_mm)) return false;
    from = q.p_P;
  }
  return true;
}

// Out of the welded bounding box grown by `r` mm along each torch axis, over its top, back down to the approach
// point of start `s` (layer `l`). The crossing is the move into the new layer, so a positioner that turns per layer
// turns while the torch is above the part.
Route OverTheTop(const WeldedGrid& welded, double r, const PassEnd& from, const PathPoint& s, std::size_t l,
                 const PathPoint& approach) {
  const Vector3d lo = welded.lo().array() - r, hi = welded.hi().array() + r;
  const Vector3d t_a = from.end.tool_dir_P, t_s = s.tool_dir_P;
  const Vector3d e_a = LeaveBox(from.lift.p_P, t_a, lo, hi), e_s = LeaveBox(approach.p_P, t_s, lo, hi);
  const Vector3d q_a(e_a.x(), e_a.y(), std::max(e_a.z(), hi.z())), q_s(e_s.x(), e_s.y(), std::max(e_s.z(), hi.z()));
  Route route;
  route.emplace_back(from.layer, TravelPoint(from.lift, e_a, t_a));
  route.emplace_back(from.layer, TravelPoint(from.lift, q_a, t_a));
  route.emplace_back(l, TravelPoint(s, q_s, t_s));
  route.emplace_back(l, TravelPoint(s, e_s, t_s));
  route.emplace_back(l, approach);
  return route;
}

// The travel to start `s` (layer `l`) of a pass: the planner's travel points `between`, lifted, then down to `s`
// along its torch axis from the approach point; over the top when that would come closer than `limit_mm` to the
// metal welded so far (the approach to the first pass comes from outside).
Route TravelTo(WeldedGrid& welded, double r, double limit_mm, const PassEnd& from, const Route& between,
               const PathPoint& s, std::size_t l, RetractReport* report) {
  ++report->travels;
  const PathPoint approach = Lifted(s, r);
  Route route;
  for (const auto& [layer, q] : between) route.emplace_back(layer, Lifted(q, r));
  route.emplace_back(l, approach);
  if (!from.any || RouteClear(welded, from.lift.p_P, route, limit_mm)) return route;
  ++report->via_top;
  return OverTheTop(welded, r, from, s, l, approach);
}

}  // namespace

RetractReport AddRetracts(double clearance_mm, Plan* plan) {
  RetractReport report;
  if (!(clearance_mm > 0.0) || plan->layers.empty()) return report;
  const double r = clearance_mm;
  const double limit = (1.0 - kSlack) * r;

  // Original points in plan order, to look one ahead across layers.
  std::vector<std::pair<std::size_t, std::size_t>> order;
  for (std::size_t l = 0; l < plan->layers.size(); ++l) {
    for (std::size_t i = 0; i < plan->layers[l].points.size(); ++i) order.emplace_back(l, i);
  }
  auto at = [&](std::size_t k) -> const PathPoint& { return plan->layers[order[k].first].points[order[k].second]; };

  PathOut out(plan->layers.size());
  WeldedGrid welded(std::max(r, 5.0));
  PassEnd pass_end;
  Route between;  // the planner's travel points after the end of the previous pass
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t l = order[k].first;
    const PathPoint& p = at(k);
    const bool next_welds = k + 1 < order.size() && at(k + 1).weld;
    if (p.weld) {
      if (k > 0) welded.Add(at(k - 1).p_P, p.p_P);
      out.Push(l, p);
      if (!next_welds) {
        // End of a pass: lift along the torch axis.
        pass_end = PassEnd{p, Lifted(p, r), l, true};
        out.Push(l, pass_end.lift);
        between.clear();
      }
    } else if (!next_welds) {
      between.emplace_back(l, p);  // a travel point on the way; decided at the next start
    } else {
      // p is the start S of a pass.
      for (const auto& [layer, q] : TravelTo(welded, r, limit, pass_end, between, p, l, &report)) out.Push(layer, q);
      out.Push(l, p);
      between.clear();
    }
  }
  // Travel points after the last pass stay, lifted.
  for (const auto& [layer, q] : between) out.Push(layer, Lifted(q, r));

  for (std::size_t l = 0; l < plan->layers.size(); ++l) plan->layers[l].points = std::move(out.layer(l));
  return report;
}

}  // namespace waam::planner
