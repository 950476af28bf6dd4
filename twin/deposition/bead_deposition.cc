// Bead deposition: footprint of each path step, ground search along the torch axis, and a water-level fill under the
// parabolic cap of 003 eq. 3.2 that puts exactly the section area (eq. 3.3) times the step length into the part.
#include "twin/deposition/bead_deposition.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <cmath>
#include <limits>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "models/core/progress.h"

namespace waam::twin {
namespace {

constexpr double kNoGround = -std::numeric_limits<double>::infinity();
// Free voxels less than this many voxels below the top of the ground in a tilted column are pinholes (see below).
constexpr double kPinholeDepth = 1.5;
// A segment keeps the torch frame of the metal laid before it while its torch axis is within this angle of it, rad.
constexpr double kFrameHoldRad = 2.0 * kPi / 180.0;

// Where the torch axis turned since the metal below was laid, a column of this segment's lattice cuts across the old
// columns and sees their top jagged at voxel scale: free voxels can lie just below the highest solid one (j). Molten
// metal fills them, so those less than 1.5 voxels below it are moved just above it (their height set to its height)
// and filled first (a wall turning 2.5 deg per layer kept 205 such pinholes without this, 1 with it; test
// TorchTurningBetweenLayersLeavesNoPinholes). Only for tilted columns: a grid column's voxels are one pitch apart and
// a free voxel under its top is a real void. Returns the index of the first voxel to fill.
std::size_t PinholesOnTheGround(std::vector<internal::ColumnVoxel>& voxels, std::size_t begin, std::size_t j,
                                const VoxelGrid& grid) {
  const double top = voxels[j].height_mm;
  const double depth = kPinholeDepth * grid.voxel_mm();
  std::size_t p = j;
  while (p > begin && voxels[p - 1].height_mm > top - depth) --p;
  if (p == j) return j + 1;
  // Solid voxels first (in height order), then the free ones.
  const auto first_free = std::stable_partition(
      voxels.begin() + static_cast<std::ptrdiff_t>(p), voxels.begin() + static_cast<std::ptrdiff_t>(j + 1),
      [&](const internal::ColumnVoxel& cv) { return grid.Solid(cv.index); });
  for (auto it = first_free; it != voxels.begin() + static_cast<std::ptrdiff_t>(j + 1); ++it) it->height_mm = top;
  return static_cast<std::size_t>(first_free - voxels.begin());
}

}  // namespace

struct Depositor::Column {
  int i0 = 0;        // lattice cell of the torch frame (internal::TorchFrame), first axis
  int i1 = 0;        // second axis
  double d_mm = 0.0; // lateral distance from the path, mm
  double u_mm = 0.0; // distance along the segment (clamped to it), mm
  double ground_mm = 0.0;  // top of the solid under the column, along the build direction, mm (or kNoGround)
  std::size_t begin = 0;   // the column's voxels in the step's buffer, by increasing height: [begin, end)
  std::size_t end = 0;
  std::size_t floor = 0;   // the first voxel above the ground (voxels below it in the column are not filled)
  bool full = false;       // the voxels were collected over the whole reach of the fill, not a window
  double from_mm = 0.0;    // lowest height collected, mm
  double m0 = 0.0;         // grid-aligned column: voxel height index (height / v - 1/2) of its first voxel
  std::size_t lo = 0;      // the voxels to fill, set by the level search: [lo, hi)
  std::size_t hi = 0;
};

// One segment of a pass (points i - 1 to i) seen in its torch frame's column plane, with the columns it owns.
struct Depositor::Segment {
  std::size_t i = 0;
  double len3_mm = 0.0;          // length in space, mm
  double len2_mm = 0.0;          // length in the column plane, mm
  std::vector<Column> columns;   // by distance along the segment, then lattice cell
};

// What the fill of one pass carries from segment to segment.
struct Depositor::PassFill {
  std::uint32_t bead = 0;
  std::vector<double> times;     // from the arc start at each point, s
  BeadRecord record;
  double debt = 0.0;             // volume owed to the part by earlier steps (voxel rounding), mm^3
};

namespace {

// The pool stands at most 1.5 h (kStopBlobHeights x h at the end of a pass) above the highest ground under it (see
// StepFill::SettleLevel).
constexpr double kStopBlobHeights = 4.0;

// Distance from the point c to the segment pq (all in the column plane), mm.
double DistanceToSegment(const Eigen::Vector2d& c, const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  const Eigen::Vector2d pq = q - p;
  const double len2 = pq.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((c - p).dot(pq) / len2, 0.0, 1.0) : 0.0;
  return (c - (p + t * pq)).norm();
}

// Segments of the same bead near segment i along the path (within `window_mm` of arc length), in the column plane.
struct Rivals {
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> segments;  // (start, end)
  std::vector<bool> before;                                           // true for segments before segment i
};

Rivals RivalsOf(const std::vector<ExecutedPoint>& pts, std::size_t i, double window_mm,
                const internal::TorchFrame& frame) {
  Rivals rivals;
  for (std::size_t j = i; j-- > 1;) {
    if (pts[i - 1].s_mm - pts[j].s_mm > window_mm) break;
    rivals.segments.emplace_back(frame.Plane(pts[j - 1].p_P), frame.Plane(pts[j].p_P));
    rivals.before.push_back(true);
  }
  for (std::size_t j = i + 1; j < pts.size(); ++j) {
    if (pts[j - 1].s_mm - pts[i].s_mm > window_mm) break;
    rivals.segments.emplace_back(frame.Plane(pts[j - 1].p_P), frame.Plane(pts[j].p_P));
    rivals.before.push_back(false);
  }
  return rivals;
}

// Cold start (Ding Fig. 1, 003 sec. 1.3.3.2: lower penetration at the start, so the bead stands higher): the first
// metal meets a cold base, wets it poorly and sets where it lands, a hump draped over the ground under it; it does
// not run into the valleys under its footprint as the steady hot pool does. Fades linearly to the levelled pool over
// start_length_mm. Returns the drape in [0, 1] at arc length s_mm.
double ColdStartDrape(const twin::SimulationSettings& settings, double s_mm) {
  return settings.start_wetting == twin::StartWetting::kCold && settings.start_length_mm > 0.0
             ? std::clamp(1.0 - s_mm / settings.start_length_mm, 0.0, 1.0)
             : 0.0;
}

}  // namespace

// The fill of one step (see FillStep): the heights along the torch axis it can reach, its columns' voxels collected
// into the depositor's scratch buffer, the ground under each column and the level of the pool.
class Depositor::StepFill {
 public:
  StepFill(const VoxelGrid& grid, std::vector<internal::ColumnVoxel>& voxels, const internal::TorchFrame& frame,
           const BeadSection& section, double zeta_tcp_mm, bool last_step, double drape, double edge_sag_factor);

  // Collects each column's voxels and finds its ground; sets the lowest, highest and centre grounds.
  void FindGrounds(std::vector<Column>& columns);
  // Sets each column's [lo, hi) to the voxels under the pool at the lowest level that holds `target_voxels`.
  void SettleLevel(std::vector<Column>& columns, long target_voxels);

 private:
  void Collect(Column& c, double lo, double hi);
  bool Search(Column& c);
  void SearchWindows(std::vector<Column>& columns);
  std::size_t FirstAbove(const Column& c, double height, bool strictly) const;
  long Count(std::vector<Column>& columns, double level, bool store) const;

  const VoxelGrid& grid_;
  std::vector<internal::ColumnVoxel>& voxels_;
  const internal::TorchFrame& frame_;
  const double v_;          // voxel pitch, mm
  const double h_;          // bead height, mm
  const double w_;          // bead width, mm
  const double zeta_tcp_mm_;
  const double drape_;
  const double edge_sag_factor_;
  // Heights of voxel centres along the torch axis, mm: the crown, the lowest and highest ground searched, the whole
  // reach of the fill and the window most columns need.
  double start_mm_ = 0.0, down_mm_ = 0.0, up_mm_ = 0.0;
  double reach_lo_ = 0.0, reach_hi_ = 0.0, window_lo_ = 0.0, window_hi_ = 0.0;
  double cap_h_ = 0.0;      // highest the pool stands above the highest ground, mm
  double sag_ = 0.0;        // deepest the metal runs below the crown over air, mm
  // Set by FindGrounds, mm.
  double lowest_ = 0.0, highest_ = 0.0, centre_ground_ = 0.0, air_floor_ = 0.0;
};

Depositor::StepFill::StepFill(const VoxelGrid& grid, std::vector<internal::ColumnVoxel>& voxels,
                              const internal::TorchFrame& frame, const BeadSection& section, double zeta_tcp_mm,
                              bool last_step, double drape, double edge_sag_factor)
    : grid_(grid), voxels_(voxels), frame_(frame), v_(grid.voxel_mm()), h_(section.height_mm),
      w_(section.width_mm), zeta_tcp_mm_(zeta_tcp_mm), drape_(drape), edge_sag_factor_(edge_sag_factor) {
  const double v = v_;
  const double h = h_;
  // Ground under each column: from the voxel at the crown (zeta + h) down to 4 h + 2 mm below the TCP, or up past
  // the part's top when that voxel is already metal. Heights are those of voxel centres along the torch axis.
  const int m_start = static_cast<int>(std::floor((zeta_tcp_mm + h) / v));
  const int m_min = static_cast<int>(std::floor((zeta_tcp_mm - 4.0 * h - 2.0) / v));
  const int m_up = m_start + static_cast<int>(std::ceil(4.0 * h / v)) + 2;
  const double eps = 1e-9 * v;
  start_mm_ = (m_start + 0.5) * v + eps;
  down_mm_ = (m_min + 0.5) * v - eps;
  up_mm_ = (m_up + 0.5) * v + eps;
  // Every voxel the fill can reach: down to the air floor below the lowest ground, up to the stop blob.
  reach_lo_ = std::min(down_mm_, zeta_tcp_mm - 4.0 * h) - edge_sag_factor * h - v;
  reach_hi_ = up_mm_ + kStopBlobHeights * h + v;
  // Most columns need far less: ground a little below the TCP and the pool at most cap_h above the highest ground.
  // Each column is first collected over that window and again over the whole reach when its search runs out of it.
  cap_h_ = (last_step ? kStopBlobHeights : 1.5) * h;
  window_lo_ = std::max(reach_lo_, zeta_tcp_mm - 2.0 * h - v);
  window_hi_ = start_mm_ + 0.5 * v + cap_h_ + v;
  // Over air (no ground within reach) the metal runs down the part's side at most edge_sag_factor x h below the
  // lowest supported column, and never more than (1 + edge_sag_factor) x h below the crown.
  sag_ = (1.0 + edge_sag_factor) * h;
  voxels_.clear();
}

inline void Depositor::StepFill::Collect(Column& c, double lo, double hi) {
  c.begin = voxels_.size();
  frame_.CollectColumn(c.i0, c.i1, lo, hi, &voxels_);
  c.end = voxels_.size();
  c.full = lo <= reach_lo_ && hi >= reach_hi_;
  if (c.end > c.begin) c.m0 = std::round(voxels_[c.begin].height_mm / v_ - 0.5);
  c.from_mm = lo;
}

// Ground search of one column; false when it ran out of the collected voxels before its limits.
inline bool Depositor::StepFill::Search(Column& c) {
  c.ground_mm = kNoGround;
  c.floor = c.end;
  // The crown voxel: the last one at or below the crown height.
  const auto above = std::upper_bound(voxels_.begin() + static_cast<std::ptrdiff_t>(c.begin),
                                      voxels_.begin() + static_cast<std::ptrdiff_t>(c.end), start_mm_,
                                      [](double x, const internal::ColumnVoxel& cv) { return x < cv.height_mm; });
  std::size_t j0 = static_cast<std::size_t>(above - voxels_.begin());
  if (j0 == c.begin) return c.full;
  --j0;
  if (grid_.Solid(voxels_[j0].index)) {
    std::size_t j = j0 + 1;
    for (; j < c.end && voxels_[j].height_mm <= up_mm_; ++j) {
      if (!grid_.Solid(voxels_[j].index)) {
        c.ground_mm = voxels_[j].height_mm - 0.5 * v_;
        c.floor = j;
        return true;
      }
    }
    if (j == c.end && !c.full) return false;
    c.ground_mm = std::numeric_limits<double>::infinity();  // buried: unusable
    return true;
  }
  for (std::size_t j = j0; j > c.begin;) {
    --j;
    if (voxels_[j].height_mm < down_mm_) return true;  // no ground within reach: over air
    if (grid_.Solid(voxels_[j].index)) {
      // The pinholes under it must lie in the collected voxels too.
      if (!frame_.aligned() && !c.full && voxels_[j].height_mm - kPinholeDepth * v_ < c.from_mm) return false;
      c.ground_mm = voxels_[j].height_mm + 0.5 * v_;
      c.floor = frame_.aligned() ? j + 1 : PinholesOnTheGround(voxels_, c.begin, j, grid_);
      return true;
    }
  }
  return c.full;  // ran out of the collected voxels: of a window, search the whole reach
}

// Each column searched over its window first, over the whole reach when the window was not enough; sets the lowest
// and highest ground found.
void Depositor::StepFill::SearchWindows(std::vector<Column>& columns) {
  lowest_ = std::numeric_limits<double>::infinity();
  highest_ = -std::numeric_limits<double>::infinity();
  for (Column& c : columns) {
    Collect(c, window_lo_, window_hi_);
    if (!Search(c)) {
      Collect(c, reach_lo_, reach_hi_);
      Search(c);
    }
    // A column over air fills down to the air floor, below its window.
    if (c.ground_mm == kNoGround && !c.full) {
      Collect(c, reach_lo_, reach_hi_);
      Search(c);
    }
    if (std::isfinite(c.ground_mm)) {
      lowest_ = std::min(lowest_, c.ground_mm);
      highest_ = std::max(highest_, c.ground_mm);
    }
  }
}

void Depositor::StepFill::FindGrounds(std::vector<Column>& columns) {
  SearchWindows(columns);
  // The ground under the path: that of the supported column nearest to it (the cold start's reference).
  centre_ground_ = std::isfinite(highest_) ? highest_ : 0.0;
  double nearest = std::numeric_limits<double>::infinity();
  for (const Column& c : columns) {
    if (std::isfinite(c.ground_mm) && c.d_mm < nearest) {
      nearest = c.d_mm;
      centre_ground_ = c.ground_mm;
    }
  }
  // A buried column's ground lies above the window, or a cold start's pool follows ground well above the one under
  // the path: then the pool may reach past every window.
  if (highest_ + cap_h_ + drape_ * (highest_ - centre_ground_) > window_hi_ - v_) {
    for (Column& c : columns) {
      if (c.full) continue;
      Collect(c, reach_lo_, reach_hi_);
      Search(c);
    }
  }
  if (!std::isfinite(lowest_)) {
    lowest_ = zeta_tcp_mm_ - 4.0 * h_;
    highest_ = lowest_;
  }
  air_floor_ = lowest_ - edge_sag_factor_ * h_;
}

// Index of the first voxel of column c whose centre lies at or above `height` (above it when `strictly`). A grid
// column's centres are one pitch apart: found by arithmetic as the grid-axis fill always did; else by bisection.
inline std::size_t Depositor::StepFill::FirstAbove(const Column& c, double height, bool strictly) const {
  if (frame_.aligned()) {
    const double m = strictly ? std::floor(height / v_ - 0.5) + 1.0 : std::ceil(height / v_ - 0.5);
    return c.begin + static_cast<std::size_t>(std::clamp(m - c.m0, 0.0, static_cast<double>(c.end - c.begin)));
  }
  const auto first = voxels_.begin() + static_cast<std::ptrdiff_t>(c.begin);
  const auto last = voxels_.begin() + static_cast<std::ptrdiff_t>(c.end);
  const auto it = strictly ? std::upper_bound(first, last, height, [](double x, const internal::ColumnVoxel& cv) {
    return x < cv.height_mm;
  }) : std::lower_bound(first, last, height, [](const internal::ColumnVoxel& cv, double x) {
    return cv.height_mm < x;
  });
  return static_cast<std::size_t>(it - voxels_.begin());
}

// Number of free voxels under the pool at `level`; stores each column's [lo, hi) when `store`.
inline long Depositor::StepFill::Count(std::vector<Column>& columns, double level, bool store) const {
  const double h = h_;
  const double w = w_;
  long total = 0;
  for (Column& c : columns) {
    if (c.ground_mm == std::numeric_limits<double>::infinity()) continue;
    // A cold start's pool follows the ground instead of levelling over it (drape = 1: the section of the bead
    // laid on the ground under the path, whatever the ground does beside it).
    const double local = c.ground_mm == kNoGround ? level : level + drape_ * (c.ground_mm - centre_ground_);
    const double top = local - 4.0 * h / (w * w) * c.d_mm * c.d_mm;
    const double bottom = c.ground_mm == kNoGround ? std::max(air_floor_, level - sag_) : local - sag_;
    // Voxels with centres in [bottom, top], and above the ground voxel.
    std::size_t lo = FirstAbove(c, bottom, false);
    if (c.ground_mm != kNoGround) lo = std::max(lo, c.floor);
    const std::size_t hi = FirstAbove(c, top, true);
    if (store) {
      c.lo = lo;
      c.hi = std::max(lo, hi);
    }
    if (hi > lo) total += static_cast<long>(hi - lo);
  }
  return total;
}

void Depositor::StepFill::SettleLevel(std::vector<Column>& columns, long target_voxels) {
  double lo_level = air_floor_ - sag_ - v_;
  // The molten pool cannot stand higher than 1.5 h above the highest ground under it: what does not fit (a step
  // that owns few columns, e.g. a short chord at a sharp turn) is carried to the next steps of the pass instead of
  // piling up in a spike. The last step of a pass takes what is left up to a stop blob of kStopBlobHeights x h;
  // metal beyond that had nowhere to go (the path runs where the part is already full, e.g. a degenerate inner
  // contour) and is not placed: it shows as deposited < expected volume, which the report flags.
  double hi_level = highest_ + h_ + v_ * (static_cast<double>(target_voxels) + 2.0);
  hi_level = std::min(hi_level, highest_ + cap_h_);
  for (int iter = 0; iter < 48 && hi_level - lo_level > 1e-4 * v_; ++iter) {
    const double mid = 0.5 * (lo_level + hi_level);
    (Count(columns, mid, false) >= target_voxels ? hi_level : lo_level) = mid;
  }
  Count(columns, hi_level, true);
}

Depositor::Depositor(const twin::SimulationSettings& settings)
    : settings_(settings), grid_((ValidateSimulationSettings(settings), settings.voxel_mm), settings.max_voxels) {}

// Fills one step. The molten metal settles under a cap z = L - 4h/w^2 y^2 (eq. 3.2 shifted to the water level L, z
// along the torch axis, y across the path in the plane perpendicular to it): each column takes the free voxels between
// its ground (or, over air past a free edge, (1 + sag) h under the crown) and the cap. L is the lowest level whose
// voxels hold the step's volume, so valleys fill first. `drape` in [0, 1] is the part of a cold start that does not
// level (see ColdStartDrape): each supported column's cap and floor are shifted by drape x (its ground - the ground
// under the path).
double Depositor::FillStep(std::vector<Column>& columns, const BeadSection& section, double target_mm3,
                           double zeta_tcp_mm, const internal::TorchFrame& frame, const VoxelData& data,
                           bool last_step, double drape) {
  const double v = grid_.voxel_mm();
  const long target_voxels = std::lround(target_mm3 / (v * v * v));
  if (target_voxels <= 0 || columns.empty()) return 0.0;
  StepFill fill(grid_, column_voxels_, frame, section, zeta_tcp_mm, last_step, drape, settings_.edge_sag_factor);
  fill.FindGrounds(columns);
  fill.SettleLevel(columns, target_voxels);
  long placed = 0;
  for (const Column& c : columns) {
    for (std::size_t j = c.lo; j < c.hi; ++j) {
      if (grid_.Set(column_voxels_[j].index, data)) ++placed;
    }
  }
  return static_cast<double>(placed) * v * v * v;
}

int Depositor::LayerOf(const VoxelData& data) const {
  const BeadRecord& bead = beads_[data.bead];
  const auto& starts = bead.layer_starts;
  const auto after = std::upper_bound(starts.begin(), starts.end(), data.time_s,
                                      [](float t, const std::pair<float, int>& start) { return t < start.first; });
  return after == starts.begin() ? bead.layer : std::prev(after)->second;
}

// The bead is swept in the torch frame: its footprint is a lattice at voxel pitch in the plane perpendicular to the
// torch axis, and each lattice cell a column of voxels growing along the axis, towards the torch. A torch that turns
// a little keeps the lattice of the metal before it (within kFrameHoldRad), so neighbouring segments and layers
// share their columns: seams between lattices, where a voxel can be left to neither, only come where the torch has
// turned further. A grid-aligned torch always gets the grid.
internal::TorchFrame Depositor::HoldFrame(const ExecutedPoint& A, const ExecutedPoint& B) {
  const Eigen::Vector3d tool = A.tool_dir_P + B.tool_dir_P;
  const internal::TorchFrame candidate(tool.norm() > 1e-9 ? tool : B.tool_dir_P, grid_.voxel_mm());
  if (!held_frame_ || candidate.aligned() || held_frame_->aligned() ||
      candidate.axis().dot(held_frame_->axis()) < std::cos(kFrameHoldRad)) {
    held_frame_ = candidate;
  }
  return *held_frame_;
}

// The lattice columns within reach of segment i that it owns. Segments of the same bead near it along the path
// (within a bead width of arc length) are its rivals: a column belongs to the nearest of them only, so a bead never
// covers its own footprint twice (corners, tight arcs), while parts of the path farther along (the next raster
// line, a crossing) overlap it as real beads do.
Depositor::Segment Depositor::SegmentColumns(const ExecutedPass& pass, std::size_t i,
                                             const internal::TorchFrame& frame) const {
  const double v = grid_.voxel_mm();
  const ExecutedPoint& A = pass.points[i - 1];
  const ExecutedPoint& B = pass.points[i];
  Segment segment;
  segment.i = i;
  segment.len3_mm = (B.p_P - A.p_P).norm();
  const Eigen::Vector2d A2 = frame.Plane(A.p_P);
  const Eigen::Vector2d B2 = frame.Plane(B.p_P);
  const double L2 = (B2 - A2).norm();
  segment.len2_mm = L2;
  const Eigen::Vector2d unit = L2 > 1e-9 ? Eigen::Vector2d((B2 - A2) / L2) : Eigen::Vector2d(1.0, 0.0);
  const Rivals rivals = RivalsOf(pass.points, i, B.bead_width_mm, frame);
  const double width_factor = std::max({1.0, settings_.start_width_factor, settings_.stop_width_factor});
  const double r_max = (0.5 + settings_.edge_spread_factor) * B.bead_width_mm * width_factor;
  const Eigen::Vector2d lo = A2.cwiseMin(B2) - Eigen::Vector2d::Constant(r_max + v);
  const Eigen::Vector2d hi = A2.cwiseMax(B2) + Eigen::Vector2d::Constant(r_max + v);
  for (int i0 = static_cast<int>(std::floor(lo.x() / v)); i0 <= static_cast<int>(std::floor(hi.x() / v)); ++i0) {
    for (int i1 = static_cast<int>(std::floor(lo.y() / v)); i1 <= static_cast<int>(std::floor(hi.y() / v)); ++i1) {
      const Eigen::Vector2d c((i0 + 0.5) * v, (i1 + 0.5) * v);
      const double u = std::clamp((c - A2).dot(unit), 0.0, L2);
      const double d = (c - (A2 + unit * u)).norm();
      if (d > r_max) continue;
      bool mine = true;
      for (std::size_t r = 0; r < rivals.segments.size() && mine; ++r) {
        const double dr = DistanceToSegment(c, rivals.segments[r].first, rivals.segments[r].second);
        // Ties (the outside of a corner, nearest to the shared vertex) go to the earlier segment.
        mine = rivals.before[r] ? dr > d : dr >= d;
      }
      if (!mine) continue;
      Column column;
      column.i0 = i0;
      column.i1 = i1;
      column.d_mm = d;
      column.u_mm = u;
      segment.columns.push_back(column);
    }
  }
  std::sort(segment.columns.begin(), segment.columns.end(), [](const Column& x, const Column& y) {
    return x.u_mm != y.u_mm ? x.u_mm < y.u_mm : (x.i0 != y.i0 ? x.i0 < y.i0 : x.i1 < y.i1);
  });
  return segment;
}

// Steps follow the columns: each takes whole rows of columns (about `step` of path) and exactly the volume of the
// path length between the midpoints to its neighbours, so no row gets a double share (no aliasing ridges).
void Depositor::FillSegment(const ExecutedPass& pass, const Segment& segment, const internal::TorchFrame& frame,
                            PassFill& fill) {
  const double step = settings_.step_mm > 0.0 ? settings_.step_mm : grid_.voxel_mm();
  const std::size_t i = segment.i;
  const ExecutedPoint& A = pass.points[i - 1];
  const ExecutedPoint& B = pass.points[i];
  const std::vector<Column>& cols = segment.columns;
  const double L2 = segment.len2_mm;
  const double len3 = segment.len3_mm;
  const double scale = L2 > 1e-9 ? len3 / L2 : 0.0;
  std::size_t first = 0;
  double boundary = 0.0;
  std::vector<Column> chunk;
  while (first < cols.size() || (cols.empty() && boundary == 0.0)) {
    std::size_t last = first;
    while (last < cols.size() && cols[last].u_mm <= cols[first].u_mm + 0.999 * step) ++last;
    // Extend to the end of the row of equal u.
    while (last < cols.size() && last > first && cols[last].u_mm - cols[last - 1].u_mm < 1e-9) ++last;
    const double next_boundary = last < cols.size() ? 0.5 * (cols[last - 1].u_mm + cols[last].u_mm) : L2;
    const double span3 = L2 > 1e-9 ? (next_boundary - boundary) * scale : len3;
    const double f = L2 > 1e-9 ? 0.5 * (boundary + next_boundary) / L2 : 0.5;
    const double s = A.s_mm + f * len3;
    const BeadSection section = SectionAt(pass, i, s, settings_);
    const double volume = section.Area() * span3;
    fill.record.expected_volume_mm3 += volume;
    chunk.clear();
    for (std::size_t c = first; c < last; ++c) {
      if (cols[c].d_mm <= (0.5 + settings_.edge_spread_factor) * section.width_mm) chunk.push_back(cols[c]);
    }
    const double zeta_tcp = frame.Height((1.0 - f) * A.p_P + f * B.p_P);
    VoxelData data;
    data.bead = fill.bead;
    data.time_s =
        static_cast<float>(pass.start_time_s + fill.times[i - 1] + (s - A.s_mm) / std::max(B.speed_mm_s, 1e-9));
    const bool last_step = i + 1 == pass.points.size() && last == cols.size();
    const double placed =
        FillStep(chunk, section, volume + fill.debt, zeta_tcp, frame, data, last_step, ColdStartDrape(settings_, s));
    fill.debt += volume - placed;
    fill.record.deposited_volume_mm3 += placed;
    boundary = next_boundary;
    first = last;
    if (cols.empty()) break;
  }
}

std::uint32_t Depositor::DepositPass(const ExecutedPass& pass) {
  const auto wall_start = std::chrono::steady_clock::now();
  const auto& pts = pass.points;
  build_time_s_ = pass.start_time_s;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    build_time_s_ += (pts[i].p_P - pts[i - 1].p_P).norm() / pts[i].speed_mm_s;
  }
  PassFill fill;
  fill.bead = static_cast<std::uint32_t>(beads_.size());
  fill.times = PassTimes(pass);
  BeadRecord& record = fill.record;
  record.start_time_s = pass.start_time_s;
  record.layer = pass.layer;
  record.length_mm = pass.length_mm();
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const int before = record.layer_starts.empty() ? pass.layer : record.layer_starts.back().second;
    if (pts[i].layer > before) {
      record.layer_starts.emplace_back(static_cast<float>(pass.start_time_s + fill.times[i - 1]), pts[i].layer);
    }
  }
  for (std::size_t i = 1; i < pts.size(); ++i) {
    if ((pts[i].p_P - pts[i - 1].p_P).norm() < 1e-9) continue;
    const internal::TorchFrame frame = HoldFrame(pts[i - 1], pts[i]);
    FillSegment(pass, SegmentColumns(pass, i, frame), frame, fill);
  }
  expected_volume_mm3_ += record.expected_volume_mm3;
  weld_length_mm_ += record.length_mm;
  beads_.push_back(record);
  deposition_wall_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return fill.bead;
}

Depositor DepositPlan(const planner::Plan& plan, const twin::SimulationSettings& settings,
                      double rapid_speed_mm_s, Progress* progress) {
  Depositor depositor(settings);
  const std::vector<ExecutedPass> passes = ExecutePlan(plan, settings, rapid_speed_mm_s);
  if (progress != nullptr) progress->SetTotal(passes.size());
  for (std::size_t i = 0; i < passes.size(); ++i) {
    depositor.DepositPass(passes[i]);
    if (progress != nullptr) progress->Update(i + 1);
  }
  return depositor;
}

}  // namespace waam::twin
