// Executed torch path: weld passes from the planned layers, corner blending (CNT100-like) and start/stop bead shapes.
#include "twin/deposition/executed_path.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Geometry>

#include "models/bead/csw_model.h"
#include "models/core/error.h"
#include "models/core/numbers.h"
#include "twin/deposition/curvature_width.h"

namespace waam::twin {
namespace {

ExecutedPoint FromPathPoint(const planner::PathPoint& p) {
  ExecutedPoint e;
  e.p_P = p.p_P;
  e.tool_dir_P = p.tool_dir_P.normalized();
  e.bead_width_mm = p.bead_width_mm;
  e.bead_height_mm = p.bead_height_mm;
  e.speed_mm_s = p.speed_mm_s;
  return e;
}

void AccumulateArcLength(ExecutedPass* pass) {
  double s = 0.0;
  for (std::size_t i = 0; i < pass->points.size(); ++i) {
    if (i > 0) s += (pass->points[i].p_P - pass->points[i - 1].p_P).norm();
    pass->points[i].s_mm = s;
  }
}

}  // namespace

std::vector<double> PassTimes(const ExecutedPass& pass) {
  std::vector<double> t(pass.points.size(), 0.0);
  for (std::size_t i = 1; i < pass.points.size(); ++i) {
    t[i] = t[i - 1] + (pass.points[i].s_mm - pass.points[i - 1].s_mm) / std::max(pass.points[i].speed_mm_s, 1e-9);
  }
  return t;
}

ExecutedPass BlendPass(const std::vector<ExecutedPoint>& raw, const twin::SimulationSettings& settings,
                       double voxel_mm) {
  ExecutedPass pass;
  // Drop repeated points: they carry no direction.
  std::vector<ExecutedPoint> pts;
  for (const ExecutedPoint& p : raw) {
    if (pts.empty() || (p.p_P - pts.back().p_P).norm() > 1e-9) pts.push_back(p);
  }
  if (pts.size() < 3 || settings.blend == twin::Blend::kNone) {
    pass.points = pts;
    AccumulateArcLength(&pass);
    return pass;
  }
  pass.points.push_back(pts.front());
  // The arc at each interior vertex is tangent to both segments; its tangent length is at most half of each segment,
  // so neighbouring arcs never overlap (the TCP passes near, not through, the programmed vertex).
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    const Eigen::Vector3d& prev = pts[i - 1].p_P;
    const Eigen::Vector3d& vertex = pts[i].p_P;
    const Eigen::Vector3d& next = pts[i + 1].p_P;
    const double len_in = (vertex - prev).norm();
    const double len_out = (next - vertex).norm();
    const Eigen::Vector3d a = (vertex - prev) / len_in;
    const Eigen::Vector3d b = (next - vertex) / len_out;
    const double turn = std::acos(std::clamp(a.dot(b), -1.0, 1.0));  // deflection angle, rad
    double radius = settings.blend == twin::Blend::kFixed ? settings.blend_radius_mm : pts[i].speed_mm_s * settings.blend_time_s;
    if (turn < 1e-3 || turn > kPi - 1e-3 || radius <= 0.0) {
      pass.points.push_back(pts[i]);
      continue;
    }
    double tangent = radius * std::tan(turn / 2.0);
    tangent = std::min(tangent, 0.5 * std::min(len_in, len_out));
    radius = tangent / std::tan(turn / 2.0);
    const Eigen::Vector3d axis = a.cross(b).normalized();
    const Eigen::Vector3d t_in = vertex - a * tangent;
    const Eigen::Vector3d center = t_in + axis.cross(a) * radius;
    const Eigen::Vector3d u0 = t_in - center;
    // Chords no longer than a voxel and no more than 10 degrees of turn each.
    const int n = std::max(1, static_cast<int>(std::ceil(std::max(turn / (10.0 * kPi / 180.0),
                                                                  radius * turn / std::max(voxel_mm, 1e-3)))));
    for (int k = 0; k <= n; ++k) {
      ExecutedPoint e = pts[k == n ? i + 1 : i];
      e.bead_width_mm = pts[i].bead_width_mm;
      e.bead_height_mm = pts[i].bead_height_mm;
      e.speed_mm_s = pts[i].speed_mm_s;
      e.tool_dir_P = (pts[i].tool_dir_P + pts[i + 1].tool_dir_P * (static_cast<double>(k) / n)).normalized();
      e.p_P = center + Eigen::AngleAxisd(turn * k / n, axis) * u0;
      pass.points.push_back(e);
    }
    // The move out of the arc keeps the next point's bead and speed.
    pass.points.back().bead_width_mm = pts[i + 1].bead_width_mm;
    pass.points.back().bead_height_mm = pts[i + 1].bead_height_mm;
  }
  pass.points.push_back(pts.back());
  AccumulateArcLength(&pass);
  return pass;
}

std::vector<ExecutedPass> ExecutePlan(const planner::Plan& plan, const twin::SimulationSettings& settings,
                                      double rapid_speed_mm_s) {
  WAAM_THROW_UNLESS(rapid_speed_mm_s > 0.0, "simulate: rapid speed = " << rapid_speed_mm_s << " mm/s: must be > 0");
  const models::CswModel* csw = nullptr;
  if (settings.curvature_width == twin::CurvatureWidth::kCsw) {
    csw = settings.csw.get();
    WAAM_DEMAND(csw != nullptr);  // loaded with the scenario
  }
  std::vector<ExecutedPass> passes;
  double time_s = 0.0;
  // A run may carry over into the next layer when that layer's first move is a weld move (continuous spiral); the
  // pass then keeps the layer it started in.
  std::vector<ExecutedPoint> run;
  int run_layer = 0;
  auto flush = [&]() {
    if (run.size() >= 2) {
      double length = 0.0;
      for (std::size_t i = 1; i < run.size(); ++i) length += (run[i].p_P - run[i - 1].p_P).norm();
      ExecutedPass pass = BlendPass(run, settings, settings.voxel_mm);
      if (csw) ApplyCurvatureWidth(*csw, settings.csw_min_radius_mm, &pass);
      pass.layer = run_layer;
      pass.start_time_s = time_s;
      // Time of the pass along the executed path at the planned speeds.
      for (std::size_t i = 1; i < pass.points.size(); ++i) {
        time_s += (pass.points[i].p_P - pass.points[i - 1].p_P).norm() / pass.points[i].speed_mm_s;
      }
      if (pass.points.size() >= 2 && length > 0.0) passes.push_back(std::move(pass));
    }
    run.clear();
  };
  const planner::PathPoint* last = nullptr;  // the previous layer's last point
  for (const planner::LayerPath& layer : plan.layers) {
    for (std::size_t i = 0; i < layer.points.size(); ++i) {
      const planner::PathPoint& p = layer.points[i];
      const planner::PathPoint* from = i > 0 ? &layer.points[i - 1] : last;
      if (from != nullptr && p.weld) {
        WAAM_THROW_UNLESS(p.speed_mm_s > 0.0 && p.bead_width_mm > 0.0 && p.bead_height_mm > 0.0,
                          "simulate: layer " << layer.index << " point " << i << ": weld move needs speed, bead "
                          "width and height > 0 (got " << p.speed_mm_s << " mm/s, " << p.bead_width_mm << " mm, "
                          << p.bead_height_mm << " mm)");
        if (run.empty()) {
          run.push_back(FromPathPoint(*from));
          run.back().layer = layer.index;
          run_layer = layer.index;
        }
        run.push_back(FromPathPoint(p));
        run.back().layer = layer.index;
      } else {
        flush();
        // An arc-off move, the one into a layer included, at the rapid speed.
        if (from != nullptr) time_s += (p.p_P - from->p_P).norm() / rapid_speed_mm_s;
      }
    }
    if (!layer.points.empty()) last = &layer.points.back();
  }
  flush();
  return passes;
}

BeadSection SectionAt(const ExecutedPass& pass, std::size_t segment, double s_mm,
                      const twin::SimulationSettings& settings) {
  const ExecutedPoint& p = pass.points[std::min(segment, pass.points.size() - 1)];
  BeadSection section{p.bead_width_mm, p.bead_height_mm};
  const double length = pass.length_mm();
  // Linear blend of the start and stop shapes (Ding Fig. 1, 003 Fig. 5: higher at the start, sloping down into the
  // crater at the end); on a pass shorter than both they multiply.
  double hf = 1.0;
  double wf = 1.0;
  if (settings.start_length_mm > 0.0 && s_mm < settings.start_length_mm) {
    const double t = 1.0 - s_mm / settings.start_length_mm;
    hf *= 1.0 + (settings.start_height_factor - 1.0) * t;
    wf *= 1.0 + (settings.start_width_factor - 1.0) * t;
  }
  const double to_end = length - s_mm;
  const double lp = settings.stop_length_mm;
  if (lp > 0.0 && to_end < lp) {
    const double t = 1.0 - std::max(0.0, to_end) / lp;
    hf *= 1.0 + (settings.stop_height_factor - 1.0) * t;
    wf *= 1.0 + (settings.stop_width_factor - 1.0) * t;
  }
  // The crater's lip. The wire feeds at a constant rate until the arc stops (Ding sec. 4: the hybrid's arcs stop
  // abruptly, no crater fill), so the last pool length receives its full share of metal; the crater is the frozen
  // front of the pool, depressed under the arc, and its missing metal was pushed back into the pool's tail, which
  // solidified just before it. Over the stop_length_mm before the crater the bead is taller by the crater's mean
  // deficit: 1 - mean of (1 + a t)(1 + b t) over t in [0, 1] = -(a + b) / 2 - a b / 3, a and b the stop height and
  // width factors minus 1. A pass shorter than 1.25 crater lengths has no room for the lip (its metal is lost, as
  // with stop_crater: lost).
  const double lip_mm = std::min(lp, length - lp);
  // Stop factors above 1 (a stop blob, no crater) get no lip.
  if (settings.stop_crater == twin::StopCrater::kLip && lp > 0.0 && lip_mm >= 0.25 * lp && to_end >= lp && to_end < lp + lip_mm) {
    const double a = settings.stop_height_factor - 1.0;
    const double b = settings.stop_width_factor - 1.0;
    const double deficit = -(a + b) / 2.0 - a * b / 3.0;
    if (deficit > 0.0) hf *= 1.0 + deficit * lp / lip_mm;
  }
  section.width_mm *= wf * p.width_factor;
  section.height_mm *= hf / p.width_factor;
  return section;
}

}  // namespace waam::twin
