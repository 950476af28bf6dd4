// The torch path as the robot really executes it: weld passes with blended corners and the bead section along them.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "models/bead/parabolic_bead.h"
#include "planner/path/tool_path.h"
#include "twin/simulation_settings.h"

namespace waam::twin {

// One point of an executed weld pass (part frame P).
struct ExecutedPoint {
  Eigen::Vector3d p_P = Eigen::Vector3d::Zero();          // TCP, mm
  Eigen::Vector3d tool_dir_P = Eigen::Vector3d::UnitZ();  // unit, up the torch
  double bead_width_mm = 0.0;                             // planned width of the bead laid up to here, mm
  double bead_height_mm = 0.0;                            // planned height, mm
  double speed_mm_s = 0.0;                                // travel speed, mm/s
  double s_mm = 0.0;                                      // arc length from the start of the pass, mm
  // Width on the path's curvature over the straight-line width (CSW model, curvature_width.h); the height is divided
  // by it, so the bead's area (set by wire feed and speed) is kept.
  double width_factor = 1.0;
  int layer = 0;  // layer of the planned move that ends here (a spiral pass runs through many)
};

// One continuous weld pass: one arc start, one arc stop.
struct ExecutedPass {
  int layer = 0;
  double start_time_s = 0.0;           // time of the arc start from the start of the build, s
  std::vector<ExecutedPoint> points;   // >= 2 points
  double length_mm() const { return points.empty() ? 0.0 : points.back().s_mm; }
};

// Time from the arc start at each point of `pass`, s: the sum of (s_i - s_(i-1)) / v_i, each move at the speed of
// the point it ends at. The depositor stamps metal laid on move i at T_(i-1) + (s - s_(i-1)) / v_i (voxel time_s),
// and the distortion's deposit history reads those stamps back by the same times.
std::vector<double> PassTimes(const ExecutedPass& pass);

// The bead section at one place of a pass: the parabolic bead of the models library (003 eq. 3.1-3.3).
using BeadSection = models::ParabolicBead;

// Splits every layer of `plan` into weld passes and blends their corners as `settings.blend` says (the TCP does not
// reach a sharp vertex; the arc is tangent to both segments and at most half of each). Travel moves are timed at
// `rapid_speed_mm_s` (> 0). With settings.curvature_width = "csw" the beads widen on curves as the CSW model says
// (curvature_width.h; the model is settings.csw, which must then be loaded). Throws InputError for a weld move with a
// non-positive speed, width or height.
std::vector<ExecutedPass> ExecutePlan(const planner::Plan& plan, const twin::SimulationSettings& settings,
                                      double rapid_speed_mm_s);

// Blends the corners of one pass polyline (used by ExecutePlan; exposed for tests).
ExecutedPass BlendPass(const std::vector<ExecutedPoint>& raw, const twin::SimulationSettings& settings,
                       double voxel_mm);

// The bead section at arc length `s_mm` of `pass`, with the start and stop shapes of `settings` applied (and, with
// settings.stop_crater = lip, the crater's metal in the stop_length_mm of bead before it).
BeadSection SectionAt(const ExecutedPass& pass, std::size_t segment, double s_mm,
                      const twin::SimulationSettings& settings);

}  // namespace waam::twin
