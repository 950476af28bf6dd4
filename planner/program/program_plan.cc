// Program targets into the part frame (the inverse of eq. 5.14-5.18: world TCP pose and positioner angles back to
// the part), circular moves discretised, passes grouped into layers by height along their build direction.
#include "planner/program/program_plan.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "models/core/error.h"
#include "planner/kinematics/positioner.h"
#include "planner/plan_limits.h"
#include "planner/program/robot_program.h"

namespace waam::planner {
namespace {

Eigen::Isometry3d PartInWorld(const CellKinematics& cell, double tilt, double rotation) {
  return cell.X_WB * PartPose(cell.positioner, tilt, rotation);
}

// The circle through a, via, b, cut into chords at most `step` apart (at most kMaxArcChords of them).
struct Arc {
  bool circle = false;  // false: the three points are (nearly) on one line, or the circle is too large for doubles
  Eigen::Vector3d c, e1, e2;  // centre, and unit vectors from it to a and a quarter turn on
  double r = 0.0, end = 0.0;  // radius (mm) and the angle from a to b (rad, counter-clockwise about (via-a)x(b-a))
  int chords = 1;
};

// Most chords one circular move is cut into; a longer arc gets longer chords.
constexpr int kMaxArcChords = 100000;

Arc ArcThrough(const Eigen::Vector3d& a, const Eigen::Vector3d& via, const Eigen::Vector3d& b, double step) {
  Arc arc;
  const Eigen::Vector3d u = via - a, v = b - a;
  const Eigen::Vector3d w = u.cross(v);
  const double w2 = w.squaredNorm();
  if (w2 < 1e-12 * std::max(1.0, u.squaredNorm() * v.squaredNorm())) return arc;
  // Circumcentre of the triangle a, via, b.
  arc.c = a + (u.squaredNorm() * v - v.squaredNorm() * u).cross(w) / (2.0 * w2);
  arc.r = (a - arc.c).norm();
  arc.e1 = (a - arc.c) / arc.r;
  arc.e2 = w.normalized().cross(arc.e1);
  double t = std::atan2((b - arc.c).dot(arc.e2), (b - arc.c).dot(arc.e1));
  arc.end = t < 0.0 ? t + 2.0 * kPi : t;  // a -> via -> b runs counter-clockwise about w
  // A circle too large for doubles (a centre offset of 1e61 mm) is no circle a controller runs: a straight move.
  arc.circle = arc.c.allFinite() && std::isfinite(arc.r) && std::isfinite(arc.end) && arc.e1.allFinite() &&
               arc.e2.allFinite();
  if (arc.circle) {
    arc.chords = static_cast<int>(std::clamp(std::ceil(arc.end * arc.r / step), 1.0, double(kMaxArcChords)));
  }
  return arc;
}

// Points along the circle through a, via, b (excluding a, including b), at most `step` apart; empty when the three
// points are (nearly) on one line.
std::vector<Eigen::Vector3d> ArcPoints(const Eigen::Vector3d& a, const Eigen::Vector3d& via, const Eigen::Vector3d& b,
                                       double step) {
  const Arc arc = ArcThrough(a, via, b, step);
  if (!arc.circle) return {};
  std::vector<Eigen::Vector3d> out;
  for (int k = 1; k < arc.chords; ++k) {
    const double t = arc.end * k / arc.chords;
    out.push_back(arc.c + arc.r * (std::cos(t) * arc.e1 + std::sin(t) * arc.e2));
  }
  out.push_back(b);
  return out;
}

// The world pose of a motion's frame (not kPart, which moves with the positioner).
Eigen::Isometry3d FrameInWorld(const CellKinematics& cell, const Eigen::Isometry3d& X_WU, TargetFrame frame) {
  switch (frame) {
    case TargetFrame::kRobot: return cell.X_WR;
    case TargetFrame::kArmWorld: return ProgramUserFrame(cell);
    default: return X_WU;
  }
}

struct PassSpan {
  std::size_t first = 0, last = 0;  // [first, last) indices into the flat point list
  Eigen::Vector3d build_dir = Eigen::Vector3d::UnitZ();
  double height = 0.0;
  bool welded = false;
};

// The flat point list of an import: one point per target, arcs cut into chords.
class PointList {
 public:
  PointList(const ImportSettings& settings, internal::WarningList* notes) : settings_(settings), notes_(notes) {}

  // Appends a point of target `t` at `p_P`. `target`: the motion's own end point (notes are counted once per motion,
  // not per chord of an arc). `positioner_rad`: the program's (tilt, rotation) at the point, which the cell motion
  // then follows.
  void Add(const Eigen::Vector3d& p_P, const Eigen::Vector3d& tool_dir_P, const ResolvedTarget& t, bool target,
           const Eigen::Vector2d& positioner_rad) {
    PathPoint p;
    p.p_P = p_P;
    p.positioner_rad = positioner_rad;
    p.tool_dir_P = tool_dir_P.normalized();
    p.bead_width_mm = settings_.bead_width_mm;
    p.bead_height_mm = settings_.bead_height_mm;
    p.weld = t.weld && !points_.empty();
    if (t.speed_mm_s > 0.0) {
      p.speed_mm_s = t.speed_mm_s;
    } else if (p.weld) {
      p.speed_mm_s = settings_.weld_speed_mm_s;
      if (target) notes_->Add("weld move without a speed: the scenario's process.travel_speed_mm_min used", t.line);
    } else {
      p.speed_mm_s = settings_.rapid_speed_mm_s;
    }
    points_.push_back(p);
  }
  std::vector<PathPoint>& points() { return points_; }

 private:
  const ImportSettings& settings_;
  internal::WarningList* notes_;
  std::vector<PathPoint> points_;
};

// The chords of the circular move `m` from `prev` to `t` (without its end point), or a note when the move is
// followed as a linear one.
// The start, intermediate and end point of the circular move `m` from `prev` to `t`, in the frame its points are
// given in: P for part-frame targets, else W (the positioner's angles run linearly from the previous target's to
// this one's along it).
std::array<Eigen::Vector3d, 3> ArcCorners(const ProgramMotion& m, const ResolvedTarget& prev, const ResolvedTarget& t,
                                          const CellKinematics& cell, const Eigen::Isometry3d& X_WU) {
  if (m.frame == TargetFrame::kPart) return {prev.p_P, m.via, t.p_P};
  return {prev.X_WT.translation(), FrameInWorld(cell, X_WU, m.frame) * m.via, t.X_WT.translation()};
}

void AddArc(const ProgramMotion& m, const ResolvedTarget& prev, const ResolvedTarget& t, const CellKinematics& cell,
            const Eigen::Isometry3d& X_WU, double arc_step_mm, PointList* points, internal::WarningList* notes) {
  const bool in_part = m.frame == TargetFrame::kPart;
  const auto [a, via, b] = ArcCorners(m, prev, t, cell, X_WU);
  const std::vector<Eigen::Vector3d> arc = ArcPoints(a, via, b, arc_step_mm);
  if (arc.empty()) {
    notes->Add("circular move through three points on one line (or too large a circle): followed as a linear move", t.line);
    return;
  }
  const Eigen::Quaterniond q0(prev.X_WT.linear()), q1(t.X_WT.linear());
  double length = 0.0;
  Eigen::Vector3d last = a;
  std::vector<double> along;
  for (const Eigen::Vector3d& x : arc) along.push_back(length += (x - last).norm()), last = x;
  for (std::size_t k = 0; k + 1 < arc.size(); ++k) {
    const double f = along[k] / length;
    const double tilt = prev.tilt_rad + f * (t.tilt_rad - prev.tilt_rad);
    const double rot = prev.rotation_rad + f * (t.rotation_rad - prev.rotation_rad);
    const Eigen::Isometry3d X_PW = PartInWorld(cell, tilt, rot).inverse();
    const Eigen::Matrix3d R_WT = q0.slerp(f, q1).toRotationMatrix();
    const Eigen::Vector3d dir_W = -R_WT.col(2);
    if (in_part) {
      // Part-frame orientation: interpolate the tool direction in P.
      points->Add(arc[k], (1.0 - f) * prev.tool_dir_P + f * t.tool_dir_P, t, false, Eigen::Vector2d(tilt, rot));
    } else {
      points->Add(X_PW * arc[k], X_PW.linear() * dir_W, t, false, Eigen::Vector2d(tilt, rot));
    }
  }
}

// Passes: a run of arc-off points followed by the welded run after it, with its build direction (the mean tool
// direction of its welded points) and height along it.
std::vector<PassSpan> SplitProgramPasses(const std::vector<PathPoint>& points) {
  std::vector<PassSpan> passes;
  for (std::size_t i = 0; i < points.size();) {
    PassSpan pass;
    pass.first = i;
    while (i < points.size() && !points[i].weld) ++i;
    while (i < points.size() && points[i].weld) ++i;
    pass.last = i;
    Eigen::Vector3d dir = Eigen::Vector3d::Zero();
    int welded = 0;
    for (std::size_t k = pass.first; k < pass.last; ++k) {
      if (points[k].weld) dir += points[k].tool_dir_P, ++welded;
    }
    pass.welded = welded > 0;
    pass.build_dir = (welded > 0 && dir.norm() > 1e-9) ? Eigen::Vector3d(dir.normalized())
                                                       : points[pass.last - 1].tool_dir_P;
    double h = 0.0;
    for (std::size_t k = pass.first; k < pass.last; ++k) {
      if (points[k].weld || welded == 0) h += points[k].p_P.dot(pass.build_dir);
    }
    pass.height = h / (welded > 0 ? welded : static_cast<int>(pass.last - pass.first));
    passes.push_back(pass);
  }
  return passes;
}

// Layers: consecutive passes at the same height along the same build direction, appended to `plan`.
void GroupLayers(const std::vector<PassSpan>& passes, const std::vector<PathPoint>& points,
                 const ImportSettings& settings, Plan* plan) {
  const double tolerance =
      settings.layer_tolerance_mm > 0.0 ? settings.layer_tolerance_mm : 0.5 * settings.bead_height_mm;
  const double kSameDirection = std::cos(1.0 * kPi / 180.0);
  const PassSpan* layer_pass = nullptr;  // the first welded pass of the current layer
  for (const PassSpan& pass : passes) {
    const bool new_layer = plan->layers.empty() ||
                           (pass.welded && layer_pass != nullptr &&
                            (pass.build_dir.dot(layer_pass->build_dir) < kSameDirection ||
                             std::abs(pass.height - layer_pass->height) > tolerance));
    if (new_layer) {
      LayerPath layer;
      layer.index = static_cast<int>(plan->layers.size());
      layer.slice_in_plane = false;
      plan->layers.push_back(layer);
      layer_pass = nullptr;
    }
    LayerPath& layer = plan->layers.back();
    if (pass.welded && layer_pass == nullptr) {
      layer_pass = &pass;
      layer.build_dir_P = pass.build_dir;
      layer.z_mm = pass.height;
    }
    layer.points.insert(layer.points.end(), points.begin() + static_cast<std::ptrdiff_t>(pass.first),
                        points.begin() + static_cast<std::ptrdiff_t>(pass.last));
  }
}

// Throws InputError before any arc is cut when the targets and the chords of the circular moves would make more than
// kMaxPathPoints path points: a few kilobytes of G2 moves of radius 1e6 mm ask for 10^8 points (gigabytes, hours).
void CheckArcPointCount(const ParsedProgram& program, const std::vector<ResolvedTarget>& targets,
                        const CellKinematics& cell, const Eigen::Isometry3d& X_WU, double arc_step_mm) {
  std::size_t points = targets.size();
  for (std::size_t i = 1; i < targets.size(); ++i) {
    const ProgramMotion& m = program.motions[i];
    if (targets[i].kind != MotionKind::kCircular || !m.has_via) continue;
    const auto [a, via, b] = ArcCorners(m, targets[i - 1], targets[i], cell, X_WU);
    const Arc arc = ArcThrough(a, via, b, arc_step_mm);
    if (arc.circle) points += static_cast<std::size_t>(arc.chords) - 1;
    WAAM_THROW_UNLESS(points <= kMaxPathPoints,
                      program.name << ": line " << targets[i].line << ": the circular moves up to here are cut into "
                                   << points << " points at " << arc_step_mm << " mm, more than the limit of "
                                   << kMaxPathPoints << " per plan (this arc: radius " << arc.r << " mm, "
                                   << arc.end * arc.r / 1000.0 << " m long)");
  }
}

}  // namespace

const ProgramMotion* ProgramTool(const ParsedProgram& program) {
  const ProgramMotion* first = nullptr;
  for (const ProgramMotion& m : program.motions) {
    if (!m.has_tool) continue;
    if (m.weld) return &m;
    if (first == nullptr) first = &m;
  }
  return first;
}

std::vector<ResolvedTarget> ResolveTargets(const ParsedProgram& program, const CellKinematics& cell,
                                           const ImportSettings& settings) {
  // Joint targets put the arm where the check's tool (the program's, else the cell's torch) then finds it again.
  const ProgramMotion* tool = ProgramTool(program);
  const Eigen::Isometry3d X_FT = tool != nullptr ? tool->X_FT : cell.X_FT;
  const Eigen::Isometry3d X_WU = settings.X_WU ? *settings.X_WU : ProgramUserFrame(cell);
  std::vector<ResolvedTarget> out;
  out.reserve(program.motions.size());
  double tilt = 0.0, rotation = 0.0;
  const PositionerType type = cell.positioner.type;
  for (const ProgramMotion& m : program.motions) {
    bool missing_axis = false;
    if (m.has_positioner) {
      tilt = m.tilt_rad, rotation = m.rotation_rad;
      // A turntable's only axis is the first numbered one (E1, eax_a, GP2 J1).
      if (m.positioner_numbered && type == PositionerType::kTurntable) std::swap(tilt, rotation);
      missing_axis = (!HasAxis(type, 6) && tilt != 0.0) || (!HasAxis(type, 7) && rotation != 0.0);
      if (!HasAxis(type, 6)) tilt = 0.0;
      if (!HasAxis(type, 7)) rotation = 0.0;
    }
    const Eigen::Isometry3d X_WP = PartInWorld(cell, tilt, rotation);
    ResolvedTarget t;
    t.missing_axis = missing_axis;
    t.kind = m.kind;
    t.line = m.line;
    t.tilt_rad = tilt;
    t.rotation_rad = rotation;
    t.speed_mm_s = m.speed_mm_s;
    t.weld = m.weld;
    t.dwell_s = m.dwell_s;
    if (m.has_joints) {
      t.X_WT = cell.X_WR * ForwardKinematics(cell.arm, m.q) * X_FT;
    } else if (m.frame == TargetFrame::kPart) {
      t.X_WT = X_WP * m.X_UT;
    } else {
      t.X_WT = FrameInWorld(cell, X_WU, m.frame) * m.X_UT;
    }
    const Eigen::Isometry3d X_PT = X_WP.inverse() * t.X_WT;
    t.p_P = X_PT.translation();
    t.tool_dir_P = -X_PT.linear().col(2);
    out.push_back(t);
  }
  return out;
}

ImportedPlan ProgramToPlan(const ParsedProgram& program, const CellKinematics& cell, const ImportSettings& settings) {
  WAAM_THROW_UNLESS(!program.motions.empty(), program.name << ": the program has no motion instruction");
  WAAM_DEMAND(settings.arc_step_mm > 0.0 && settings.bead_height_mm > 0.0 && settings.bead_width_mm > 0.0);
  internal::WarningList notes;
  const std::vector<ResolvedTarget> targets = ResolveTargets(program, cell, settings);
  const Eigen::Isometry3d X_WU = settings.X_WU ? *settings.X_WU : ProgramUserFrame(cell);

  CheckArcPointCount(program, targets, cell, X_WU, settings.arc_step_mm);
  PointList points(settings, &notes);
  points.points().reserve(targets.size());
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const ResolvedTarget& t = targets[i];
    const ProgramMotion& m = program.motions[i];
    if (t.missing_axis) {
      notes.Add("positioner axis the cell lacks (cell.positioner.type " + std::string(NameOf(cell.positioner.type)) +
                    ") moved: held at 0",
                t.line);
    }
    if (t.kind == MotionKind::kCircular && i > 0 && m.has_via) {
      AddArc(m, targets[i - 1], t, cell, X_WU, settings.arc_step_mm, &points, &notes);
    } else if (t.kind == MotionKind::kCircular && !m.has_via) {
      notes.Add("circular move without its intermediate point: followed as a linear move", t.line);
    }
    points.Add(t.p_P, t.tool_dir_P, t, true, Eigen::Vector2d(t.tilt_rad, t.rotation_rad));
    points.points().back().dwell_s = t.dwell_s;
  }

  ImportedPlan out;
  out.plan.name = program.name;
  GroupLayers(SplitProgramPasses(points.points()), points.points(), settings, &out.plan);
  out.points = points.points().size();
  if (const ProgramMotion* tool = ProgramTool(program)) {
    out.plan.X_FT = tool->X_FT, out.plan.tool_name = tool->tool_name;
    for (const ProgramMotion& m : program.motions) {
      if (m.has_tool && m.has_pose && !m.X_FT.isApprox(tool->X_FT, 1e-9)) {
        notes.Add("Cartesian move with tool " + m.tool_name + ", not " + tool->tool_name + ": the check moves " +
                      tool->tool_name,
                  m.line);
      }
    }
  }
  out.warnings = program.warnings;
  for (ProgramWarning& w : notes.Take()) out.warnings.push_back(std::move(w));
  return out;
}

}  // namespace waam::planner
