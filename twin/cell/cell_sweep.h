// Continuous collision checking of a sampled motion (cell.checks.mode continuous): the motion between two samples
// is the joint-space line between them, and conservative advancement over it certifies a clearance between every
// pair of cell bodies over the whole motion, finds contacts between samples and their time of first contact.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "planner/kinematics/cell_motion.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {

struct SweepOptions {
  double contact_mm = 0.05;     // > 0: a pair closer than this is in contact (the first-contact resolution), mm
  double tolerance_mm = 0.0;    // >= 0: contacts penetrating no deeper are not reported (collision_tolerance_mm), mm
  // > 0: the certified clearance is refined until it lies within max(resolution_mm, resolution_ratio x the
  // smallest distance found) of that distance, mm and a ratio.
  double resolution_mm = 0.1;
  double resolution_ratio = 0.05;
  double probe_mm = 1.0;        // > 0: after a first contact, MuJoCo's depth is probed at this motion spacing, mm
};

// A penetrating contact the sweep found.
struct SweepContact {
  std::size_t sample = 0;      // the sample it was found at, or the sample ending the move it was found in
  double t_s = 0.0;            // time of first contact (the pair within SweepOptions::contact_mm), s
  bool between_samples = false;  // first contact strictly between two samples
  CellContact contact;         // bodies, deepest penetration MuJoCo found (at the sample or the probes), point
};

struct SweepResult {
  std::vector<SweepContact> contacts;  // in sample order
  // Lower bound on the distance between any two bodies of a tested pair over the whole motion (every stretch of
  // reachable samples and the joint-space lines between them); at most contact_mm where a contact was found, mm.
  double certified_clearance_mm = 0.0;
  double min_distance_mm = 0.0;        // the smallest distance found between two points of a pair (>= certified), mm
  std::string closest_body1, closest_body2;  // the pair of that distance
  double closest_t_s = 0.0;                  // and its time, s
  double first_contact_s = -1.0;       // time of the first contact found (-1: none), s
  std::size_t distance_queries = 0;    // pair distance bounds computed (bounding spheres or GJK)
  std::size_t gjk_queries = 0;         // of which by GJK
  std::size_t poses = 0;               // configurations whose forward kinematics were computed
  std::size_t refinements = 0;         // queries added to tighten the certified clearance
};

// Sweeps `motion` (time-stamped samples, unreachable ones break it into stretches) on `cell` with the geometry
// `geometry` (cell.CollisionGeometry(), whose `unsupported` must be empty: WAAM_DEMAND). Per pair: from a lower bound
// d on its distance at parameter s (bounding spheres, else GJK) and the bound on how fast its two shapes approach
// (the joints' travel along the line times the lever arms of the joints that move one shape and not the other), the
// next query is where the travel bound reaches d - contact_mm / 2; queries falling beyond a sample are moved back to
// it, so that one forward kinematics serves every pair due there.
// Lower bound on a distance over a stretch of motion from bounds d_a, d_b at its ends (mm) and the bound M (mm) on
// how far the two shapes can approach over it: (d_a + d_b - M) / 2, or min(d_a, d_b) when |d_a - d_b| >= M.
double IntervalBound(double d_a, double d_b, double M);

SweepResult SweepMotion(const CellModel& cell, const CellCollisionGeometry& geometry,
                        const std::vector<planner::CellSample>& motion, const SweepOptions& options);

}  // namespace waam::twin
