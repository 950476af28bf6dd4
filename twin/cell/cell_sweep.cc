// Conservative advancement over the joint-space lines between the samples of a motion (after Mirtich 1996 and
// Schwarzer, Saha, Latombe 2005: a distance lower bound and a bound on the approach speed give the next time a
// contact is possible), per pair of cell geoms, with a refinement that certifies the smallest clearance.
#include "twin/cell/cell_sweep.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "models/core/error.h"

namespace waam::twin {
namespace {

using Vec8 = Eigen::Matrix<double, 8, 1>;
constexpr double kGjkToleranceMm = 0.01;
constexpr double kSphereSkipSamples = 16.0;  // a bounding-sphere bound that reaches this far needs no GJK
constexpr double kPoseGrid = 8.0;  // samples: pairs that skip farther are queried at multiples of it
constexpr std::size_t kMaxRefinements = 20000;
constexpr int kMaxProbes = 64;

// The joints' cumulative travel along the motion: row i is the summed |q_(k+1) - q_k| over k < i, rad. Along the
// joint-space line of one move every axis moves monotonically, so a weighted sum of the rows bounds how far any
// point can have moved (each axis turns a point about it by at most its travel times its lever arm).
class Travel {
 public:
  explicit Travel(const std::vector<planner::CellSample>& motion) : rows_(motion.size(), Vec8::Zero()) {
    for (std::size_t i = 1; i < motion.size(); ++i) rows_[i] = rows_[i - 1] + (motion[i].q - motion[i - 1].q).cwiseAbs();
  }
  // The weighted travel at parameter s (sample index plus the fraction of the next move), mm for levers in mm.
  double At(const Vec8& w, double s) const {
    const std::size_t i = static_cast<std::size_t>(s);
    const double base = w.dot(rows_[i]);
    const double f = s - static_cast<double>(i);
    return f > 0.0 ? base + f * (w.dot(rows_[i + 1]) - base) : base;
  }
  // The smallest s' in (s, end] at which the weighted travel since s reaches `budget`, or `end` when it does not.
  double Advance(const Vec8& w, double s, double end, double budget) const {
    const double target = At(w, s) + budget;
    const double last = std::floor(end);
    double lo = std::floor(s), hi = lo;  // At(lo) < target; find the first integer hi with At(hi) >= target
    double step = 1.0;
    for (;;) {
      hi = std::min(last, lo + step);
      if (hi > lo && w.dot(rows_[static_cast<std::size_t>(hi)]) >= target) break;
      if (hi >= last) {
        // Not reached by the last whole sample: within the part of the move beyond it, if `end` goes there.
        if (end <= last) return end;
        const double at = std::max(s, last) + 0.0;
        const double a = At(w, last), b = At(w, last + 1.0);
        if (b <= a) return end;
        return std::clamp(std::max(last + (target - a) / (b - a), at), s, end);
      }
      lo = hi;
      step *= 2.0;
    }
    while (hi - lo > 1.0) {
      const double mid = std::floor(0.5 * (lo + hi));
      (w.dot(rows_[static_cast<std::size_t>(mid)]) >= target ? hi : lo) = mid;
    }
    const double a = w.dot(rows_[static_cast<std::size_t>(lo)]), b = w.dot(rows_[static_cast<std::size_t>(hi)]);
    const double at = lo + std::clamp((target - a) / (b - a), 0.0, 1.0);
    return std::clamp(std::max(at, s), s, end);
  }

 private:
  std::vector<Vec8> rows_;
};

// An interval between two queries of one pair whose bound may still be tightened.
struct Interval {
  int pair = 0;
  double s_a = 0.0, d_a = 0.0, s_b = 0.0, d_b = 0.0;
};

// The sweep's working state: one CellState, the travel table, and the pairs' weights.
class Sweeper {
 public:
  Sweeper(const CellModel& cell, const CellCollisionGeometry& geometry, const std::vector<planner::CellSample>& motion,
          const SweepOptions& options)
      : g_(geometry), motion_(motion), options_(options), state_(cell), travel_(motion) {
    for (const std::array<int, 2>& p : g_.pairs) {
      const Vec8& la = g_.lever_mm[p[0]];
      const Vec8& lb = g_.lever_mm[p[1]];
      Vec8 w = Vec8::Zero();
      // An axis that moves both shapes moves them as one rigid body: it does not change their distance.
      for (int j = 0; j < 8; ++j) {
        if ((la[j] > 0.0) != (lb[j] > 0.0)) w[j] = la[j] + lb[j];
      }
      weights_.push_back(w);
    }
    result_.certified_clearance_mm = std::numeric_limits<double>::infinity();
    result_.min_distance_mm = std::numeric_limits<double>::infinity();
  }

  SweepResult Run();

 private:
  double TimeAt(double s) const {
    const std::size_t i = static_cast<std::size_t>(s);
    const double f = s - static_cast<double>(i);
    return f > 0.0 ? motion_[i].t_s + f * (motion_[i + 1].t_s - motion_[i].t_s) : motion_[i].t_s;
  }
  planner::Joints8 JointsAt(double s) const {
    const std::size_t i = static_cast<std::size_t>(s);
    const double f = s - static_cast<double>(i);
    return f > 0.0 ? planner::Joints8(motion_[i].q + f * (motion_[i + 1].q - motion_[i].q)) : motion_[i].q;
  }
  // The shapes' poses at s, from the geometry's own tree (MuJoCo's mjData is set only for its collision detection).
  void PoseAt(double s) {
    if (s == posed_) return;
    ShapePosesAt(g_, JointsAt(s), &X_WG_);
    posed_ = s;
    ++result_.poses;
  }
  // Distance lower bound of pair p at the pose set last (at s): its bounding spheres' when `allow_sphere`, they are
  // no closer than the smallest distance found so far and they let the pair advance kSphereSkipSamples (or to
  // `end`), else GJK's.
  double Distance(int p, double s, double end, bool allow_sphere);
  void ContactAt(int p, double s, double end);
  void RunStretch(std::size_t r0, std::size_t r1);
  void Refine();
  double Resolution() const {
    return std::max(options_.resolution_mm, options_.resolution_ratio * result_.min_distance_mm);
  }
  void Keep(int p, double s_a, double d_a, double s_b, double d_b) {
    const double L = IntervalBound(d_a, d_b, travel_.At(weights_[p], s_b) - travel_.At(weights_[p], s_a));
    if (L < result_.min_distance_mm - Resolution()) {
      open_.push_back({p, s_a, d_a, s_b, d_b});
    } else {
      settled_ = std::min(settled_, L);
    }
  }

  const CellCollisionGeometry& g_;
  const std::vector<planner::CellSample>& motion_;
  const SweepOptions options_;
  CellState state_;
  Travel travel_;
  std::vector<Vec8> weights_;
  std::vector<Eigen::Isometry3d> X_WG_;
  double posed_ = -1.0;
  double collided_sample_ = -1.0;  // the last sample MuJoCo's contacts were collected at
  std::vector<Interval> open_;
  double settled_ = std::numeric_limits<double>::infinity();
  double deepest_ = 0.0;
  std::vector<CellContact> scratch_;
  SweepResult result_;
};

double Sweeper::Distance(int p, double s, double end, bool allow_sphere) {
  const int a = g_.pairs[p][0], b = g_.pairs[p][1];
  ++result_.distance_queries;
  const double sphere = BoundingSphereDistance(g_.shapes[a], X_WG_[a], g_.shapes[b], X_WG_[b]);
  // A bounding-sphere answer below the smallest distance found so far could lower the certified clearance for
  // want of a better bound: only those above it are taken.
  if (allow_sphere && sphere > options_.contact_mm && sphere >= result_.min_distance_mm - Resolution()) {
    // The travel is monotone in s: the sphere's budget reaches kSphereSkipSamples ahead (or `end`) when the travel
    // up to there stays within it.
    const double reach = std::min(end, std::floor(s) + kSphereSkipSamples);
    if (travel_.At(weights_[p], reach) - travel_.At(weights_[p], s) < sphere - 0.5 * options_.contact_mm) return sphere;
  }
  ++result_.gjk_queries;
  const ConvexDistance d = ShapeDistance(g_.shapes[a], X_WG_[a], g_.shapes[b], X_WG_[b], kGjkToleranceMm);
  if (d.upper_mm < result_.min_distance_mm) {
    result_.min_distance_mm = d.upper_mm;
    result_.closest_body1 = g_.body[a];
    result_.closest_body2 = g_.body[b];
    result_.closest_t_s = TimeAt(s);
  }
  return d.lower_mm;
}

// Pair p within contact_mm at s: MuJoCo's contacts at s (a sample) and at probes through the rest of the move.
void Sweeper::ContactAt(int p, double s, double end) {
  const std::string& body1 = g_.body[g_.pairs[p][0]];
  const std::string& body2 = g_.body[g_.pairs[p][1]];
  const bool at_sample = s == std::floor(s);
  // MuJoCo's contacts at `at`: every pair's at a sample, this pair's at a probe between samples.
  const auto collect = [&](double at, std::size_t sample, bool between) {
    state_.SetJoints(JointsAt(at));
    scratch_.clear();
    state_.Collide(options_.tolerance_mm, &scratch_, nullptr);
    for (CellContact& c : scratch_) {
      const bool ours = (c.body1 == body1 && c.body2 == body2) || (c.body1 == body2 && c.body2 == body1);
      if (!ours && between) continue;
      deepest_ = std::max(deepest_, c.penetration_mm);
      result_.contacts.push_back({sample, TimeAt(s), between, std::move(c)});
    }
  };
  if (at_sample && collided_sample_ != s) {
    collided_sample_ = s;
    collect(s, static_cast<std::size_t>(s), false);  // every contact MuJoCo finds there, as the discrete check would
  }
  const double next = std::min(end, std::floor(s) + 1.0);
  if (next <= s) return;
  // Probes through (s, next): the depth MuJoCo finds, keeping the deepest one for this pair.
  const double travel = travel_.At(weights_[p], next) - travel_.At(weights_[p], s);
  const int n = std::clamp(static_cast<int>(std::ceil(travel / options_.probe_mm)), 2, kMaxProbes);
  const std::size_t before = result_.contacts.size();
  for (int k = 1; k < n; ++k) collect(s + (next - s) * k / n, static_cast<std::size_t>(next), true);
  // One entry per probed move: the deepest.
  if (result_.contacts.size() > before + 1) {
    auto deepest = std::max_element(result_.contacts.begin() + before, result_.contacts.end(),
                                    [](const SweepContact& x, const SweepContact& y) {
                                      return x.contact.penetration_mm < y.contact.penetration_mm;
                                    });
    std::swap(result_.contacts[before], *deepest);
    result_.contacts.resize(before + 1);
  }
}

void Sweeper::RunStretch(std::size_t r0, std::size_t r1) {
  const double end = static_cast<double>(r1);
  using Due = std::pair<double, int>;
  std::priority_queue<Due, std::vector<Due>, std::greater<Due>> queue;
  std::vector<double> last_s(g_.pairs.size(), -1.0), last_d(g_.pairs.size(), 0.0);
  for (int p = 0; p < static_cast<int>(g_.pairs.size()); ++p) queue.push({static_cast<double>(r0), p});
  while (!queue.empty()) {
    const auto [s, p] = queue.top();
    queue.pop();
    PoseAt(s);
    const double d = Distance(p, s, end, true);
    if (last_s[p] >= 0.0) {
      if (last_d[p] <= options_.contact_mm || d <= options_.contact_mm) {
        settled_ = std::min(settled_, std::min(last_d[p], d));  // a contact stretch: no clearance to certify
      } else {
        Keep(p, last_s[p], last_d[p], s, d);
      }
    }
    last_s[p] = s;
    last_d[p] = d;
    if (d <= options_.contact_mm) ContactAt(p, s, end);
    if (s >= end) continue;
    double next;
    if (d <= options_.contact_mm) {
      next = std::min(end, std::floor(s) + 1.0);
    } else {
      next = travel_.Advance(weights_[p], s, end, d - 0.5 * options_.contact_mm);
      // Wait at the sample before: one pose serves the pairs due there; a pair that advances past kPoseGrid
      // samples waits at the last multiple of kPoseGrid before its due sample, where the far pairs meet.
      const double grid = std::floor(next / kPoseGrid) * kPoseGrid;
      if (grid > s + kPoseGrid) {
        next = grid;
      } else if (std::floor(next) > s) {
        next = std::floor(next);
      }
    }
    queue.push({next, p});
  }
}

void Sweeper::Refine() {
  while (!open_.empty() && result_.refinements < kMaxRefinements) {
    const Interval in = open_.back();
    open_.pop_back();
    const Vec8& w = weights_[in.pair];
    const double M = travel_.At(w, in.s_b) - travel_.At(w, in.s_a);
    const double L = IntervalBound(in.d_a, in.d_b, M);
    if (L >= result_.min_distance_mm - Resolution()) {
      settled_ = std::min(settled_, L);
      continue;
    }
    // Query where the two bounds cross.
    const double s = travel_.Advance(w, in.s_a, in.s_b, 0.5 * (in.d_a - in.d_b + M));
    if (s <= in.s_a || s >= in.s_b) {
      settled_ = std::min(settled_, L);
      continue;
    }
    ++result_.refinements;
    PoseAt(s);
    const double d = Distance(in.pair, s, in.s_b, false);
    Keep(in.pair, in.s_a, in.d_a, s, d);
    Keep(in.pair, s, d, in.s_b, in.d_b);
  }
  for (const Interval& in : open_) {
    const Vec8& w = weights_[in.pair];
    settled_ = std::min(settled_, IntervalBound(in.d_a, in.d_b, travel_.At(w, in.s_b) - travel_.At(w, in.s_a)));
  }
  open_.clear();
}

SweepResult Sweeper::Run() {
  std::size_t i = 0;
  while (i < motion_.size()) {
    if (!motion_[i].reachable) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < motion_.size() && motion_[j + 1].reachable) ++j;
    RunStretch(i, j);
    i = j + 1;
  }
  Refine();
  std::stable_sort(result_.contacts.begin(), result_.contacts.end(),
                   [](const SweepContact& a, const SweepContact& b) { return a.sample < b.sample; });
  for (const SweepContact& c : result_.contacts) {
    if (result_.first_contact_s < 0.0 || c.t_s < result_.first_contact_s) result_.first_contact_s = c.t_s;
  }
  result_.certified_clearance_mm = result_.contacts.empty() ? settled_ : -deepest_;
  if (!std::isfinite(result_.certified_clearance_mm)) result_.certified_clearance_mm = 0.0;
  if (!std::isfinite(result_.min_distance_mm)) result_.min_distance_mm = 0.0;
  return std::move(result_);
}

}  // namespace

// The distance is at least max(d_a - m, d_b - (M - m)) at travel m; the smallest over m in [0, M].
double IntervalBound(double d_a, double d_b, double M) {
  if (std::abs(d_a - d_b) >= M) return std::min(d_a, d_b);
  return 0.5 * (d_a + d_b - M);
}

SweepResult SweepMotion(const CellModel& cell, const CellCollisionGeometry& geometry,
                        const std::vector<planner::CellSample>& motion, const SweepOptions& options) {
  WAAM_DEMAND(geometry.unsupported.empty());
  WAAM_DEMAND(options.contact_mm > 0.0 && options.probe_mm > 0.0 && options.resolution_mm > 0.0);
  Sweeper sweeper(cell, geometry, motion, options);
  return sweeper.Run();
}

}  // namespace waam::twin
