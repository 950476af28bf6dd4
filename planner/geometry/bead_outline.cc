// Bead outlines along polylines (Clipper's open round offset with mitred inner joins) and the area they leave.
#include "planner/geometry/bead_outline.h"

#include <algorithm>
#include <cmath>

namespace waam::planner::internal {
namespace {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;

constexpr double kTwoPi = 6.283185307179586476925286766559;

// Clipper's rounding of a coordinate.
cInt Round(double value) { return value < 0 ? static_cast<cInt>(value - 0.5) : static_cast<cInt>(value + 0.5); }

struct Normal {
  double x = 0.0, y = 0.0;
};

// The right-hand unit normal of a -> b, as Clipper's GetUnitNormal (zero for a repeated point).
Normal UnitNormal(const IntPoint& a, const IntPoint& b) {
  const double dx = static_cast<double>(b.X - a.X), dy = static_cast<double>(b.Y - a.Y);
  if (dx == 0.0 && dy == 0.0) return {};
  const double f = 1.0 / std::sqrt(dx * dx + dy * dy);
  return {dy * f, -dx * f};
}

// One polyline's outline: ClipperOffset::DoOffset for etOpenRound and jtRound (clipper.cpp 6.4), with the inner
// joins replaced as the header says.
class OutlineBuilder {
 public:
  OutlineBuilder(double delta, double arc_tolerance) : delta_(delta) {
    // ClipperOffset's step of the round joins: its arc tolerance, capped at a quarter of the radius.
    const double y = std::min(arc_tolerance, 0.25 * delta);
    steps_ = std::min(kTwoPi / 2.0 / std::acos(1.0 - y / delta), delta * kTwoPi / 2.0);
    sin_ = std::sin(kTwoPi / steps_);
    cos_ = std::cos(kTwoPi / steps_);
    steps_per_rad_ = steps_ / kTwoPi;
  }

  void Build(const Path& src, Path* out) {
    src_ = &src;
    out_ = out;
    out->clear();
    const int len = static_cast<int>(src.size());
    if (len == 1) {
      double x = 1.0, y = 0.0;
      for (cInt j = 1; j <= steps_; ++j) {
        Push(src[0], x, y);
        const double x2 = x;
        x = x * cos_ - sin_ * y;
        y = x2 * sin_ + y * cos_;
      }
      return;
    }
    normals_.assign(len, {});
    half_length_.assign(len, 0.0);
    for (int j = 0; j + 1 < len; ++j) {
      normals_[j] = UnitNormal(src[j], src[j + 1]);
      half_length_[j] = 0.5 * std::hypot(static_cast<double>(src[j + 1].X - src[j].X),
                                         static_cast<double>(src[j + 1].Y - src[j].Y));
    }
    normals_[len - 1] = normals_[len - 2];
    // Forward along the right side, round the end, back along the left side, round the start.
    int k = 0;
    for (int j = 1; j < len - 1; ++j) OffsetPoint(j, &k, /*prev_segment=*/j - 1, /*next_segment=*/j);
    normals_[len - 1] = {-normals_[len - 1].x, -normals_[len - 1].y};
    sin_a_ = 0.0;
    DoRound(len - 1, len - 2);
    for (int j = len - 1; j > 0; --j) normals_[j] = {-normals_[j - 1].x, -normals_[j - 1].y};
    normals_[0] = {-normals_[1].x, -normals_[1].y};
    k = len - 1;
    for (int j = k - 1; j > 0; --j) OffsetPoint(j, &k, /*prev_segment=*/j, /*next_segment=*/j - 1);
    sin_a_ = 0.0;
    DoRound(0, 1);
  }

 private:
  void Push(const IntPoint& p, double nx, double ny) {
    out_->push_back(IntPoint(Round(static_cast<double>(p.X) + nx * delta_), Round(static_cast<double>(p.Y) + ny * delta_)));
  }

  void OffsetPoint(int j, int* k, int prev_segment, int next_segment) {
    const Normal& nk = normals_[*k];
    const Normal& nj = normals_[j];
    const IntPoint& p = (*src_)[j];
    sin_a_ = nk.x * nj.y - nj.x * nk.y;
    const double cos_a = nk.x * nj.x + nk.y * nj.y;
    if (std::fabs(sin_a_ * delta_) < 1.0) {
      if (cos_a > 0) {  // straight on: one point
        Push(p, nk.x, nk.y);
        return;
      }
    } else {
      sin_a_ = std::clamp(sin_a_, -1.0, 1.0);
    }
    if (sin_a_ * delta_ < 0) {
      // The path turns away from this side. Its two offset lines meet at p + delta (nk + nj) / (1 + cos), a
      // distance delta tan(turn / 2) from p along either segment; when that is within half of both segments, the
      // point is on both offset segments and is the bead's edge there (Clipper's loop p1, p, p2 around it lies
      // inside the bead). Otherwise (a sharp turn or short segments) Clipper's loop.
      const double along = delta_ * std::fabs(sin_a_) / (1.0 + cos_a);
      if (cos_a > 0.0 && along <= half_length_[prev_segment] && along <= half_length_[next_segment]) {
        const double f = 1.0 / (1.0 + cos_a);
        Push(p, (nk.x + nj.x) * f, (nk.y + nj.y) * f);
      } else {
        Push(p, nk.x, nk.y);
        out_->push_back(p);
        Push(p, nj.x, nj.y);
      }
    } else {
      DoRound(j, *k);
    }
    *k = j;
  }

  void DoRound(int j, int k) {
    const Normal& nk = normals_[k];
    const Normal& nj = normals_[j];
    const double a = std::atan2(sin_a_, nk.x * nj.x + nk.y * nj.y);
    const int steps = std::max(static_cast<int>(Round(steps_per_rad_ * std::fabs(a))), 1);
    double x = nk.x, y = nk.y;
    for (int i = 0; i < steps; ++i) {
      Push((*src_)[j], x, y);
      const double x2 = x;
      x = x * cos_ - sin_ * y;
      y = x2 * sin_ + y * cos_;
    }
    Push((*src_)[j], nj.x, nj.y);
  }

  double delta_;
  double steps_ = 0.0, sin_ = 0.0, cos_ = 1.0, steps_per_rad_ = 0.0;
  double sin_a_ = 0.0;
  const Path* src_ = nullptr;
  Path* out_ = nullptr;
  std::vector<Normal> normals_;
  std::vector<double> half_length_;
};

}  // namespace

void AppendBeadOutlines(const std::vector<Polyline>& lines, double radius_mm, double arc_tolerance_mm,
                        ClipperLib::Paths* outlines) {
  if (!(radius_mm > 0.0)) return;
  OutlineBuilder builder(radius_mm * kClipperUnitsPerMm, arc_tolerance_mm * kClipperUnitsPerMm);
  Path src;
  for (const Polyline& line : lines) {
    if (line.size() < 2) continue;
    // Repeated points dropped, as ClipperOffset::AddPath does.
    src.clear();
    for (const Eigen::Vector2d& p : line) {
      const IntPoint q = ToClipper(p);
      if (src.empty() || src.back() != q) src.push_back(q);
    }
    Path outline;
    builder.Build(src, &outline);
    outlines->push_back(std::move(outline));
  }
}

double AreaOutsideBeads(const ClipperLib::Paths& region_paths, const ClipperLib::Paths& outlines) {
  ClipperLib::Clipper clipper;
  clipper.AddPaths(region_paths, ClipperLib::ptSubject, true);
  clipper.AddPaths(outlines, ClipperLib::ptClip, true);
  ClipperLib::Paths left;
  clipper.Execute(ClipperLib::ctDifference, left, ClipperLib::pftNonZero, ClipperLib::pftPositive);
  // Clipper's solution has its outers positive and its holes negative: the signed areas add up to the region's.
  double area = 0.0;
  for (const Path& path : left) area += ClipperLib::Area(path);
  return area / (kClipperUnitsPerMm * kClipperUnitsPerMm);
}

}  // namespace waam::planner::internal
