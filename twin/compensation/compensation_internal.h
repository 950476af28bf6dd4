// Internals of the compensation loop: the corrections S_i estimated from a scan alone, and the central-axis shift.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/path/tool_path.h"
#include "twin/compensation/compensation.h"
#include "twin/distortion/distortion.h"
#include "twin/scanner/mesh_distance.h"
#include "twin/scanner/scan_deviation.h"

namespace waam::twin::internal {

// The scan's cross sections against the reference's, station by station along the reference axis (003 sec. 6.3.1):
// the offset of the section centre (the central axis) and the outward move of the section outline in 72 directions
// of the section plane (support function of the section, outline minus its centre: shrinkage and ovality).
struct SectionShift {
  static constexpr int kDirections = 72;
  std::vector<AxisStation> stations;      // reference axis
  std::vector<Eigen::Vector3d> t1;        // first in-plane axis of each station, transported along the axis (unit)
  std::vector<Eigen::Vector3d> shift;     // scan section centre - reference centre, in the section plane, mm
  std::vector<std::array<double, kDirections>> outline;  // outward move of the outline at angle 5k deg, mm
  std::vector<std::uint8_t> measured;     // 1: a complete scan section; 0: filled in from the measured ones
  double max_measured_mm = 0.0;           // largest |shift| over the measured stations, mm

  // The station `k` whose centre is nearest a point, its neighbour `j` on the other side of the point and the weight
  // `t` (0..1) of the neighbour: the two stations whose planes enclose the point.
  struct Bracket {
    std::size_t k = 0, j = 0;
    double t = 0.0;
  };

  // The stations enclosing `p` (mm); needs at least one station.
  Bracket Enclosing(const Eigen::Vector3d& p) const;
  // Axis offset at `p` (mm), interpolated between the two stations whose planes enclose it; zero without stations.
  Eigen::Vector3d Axis(const Eigen::Vector3d& p) const;
  // The same from the stations `b` = Enclosing(p), found once for several measures at one point.
  Eigen::Vector3d Axis(const Bracket& b) const;
  // Outward move of the outline at `p` (mm, along the in-plane direction from the reference centre to `p`).
  Eigen::Vector3d Outline(const Eigen::Vector3d& p) const;
  // The same from the stations `b` = Enclosing(p).
  Eigen::Vector3d Outline(const Eigen::Vector3d& p, const Bracket& b) const;
};

// Compares `scan` with `reference` (both surface point clouds in the part frame, mm) at reference-axis stations
// `step_mm` (> 0) apart. Stations where the scan section is incomplete (the ends) take the nearest measured values
// at the bottom, and at the top a straight-line extrapolation of the last measured axis offsets (a bend keeps
// growing; over at most 20 mm of axis, then held) and the last measured outline.
SectionShift MeasureSectionShift(const std::vector<Eigen::Vector3d>& reference,
                                 const std::vector<Eigen::Vector3d>& scan, double step_mm);

// The corrections S_i (mm, in each layer's plane) of every point of `nominal` from `scan` (deviations against
// `reference_distance`, the reference surface whose points are `reference_points`; the top rim left out) and
// `scan_points` (the whole scan, rim included, for the cross sections: a station through the rim is a whole ring).
//   method kPoints: S_i = mean of d_j n_j over the scan points near r_i in its layer band (closest-point only).
//   method kAxis:   S_i = axis offset + outline move at r_i + the same mean measured on the scan moved back by both.
std::vector<std::vector<Eigen::Vector3d>> EstimateCorrections(const planner::Plan& nominal, const ScanDeviation& scan,
                                                              const std::vector<Eigen::Vector3d>& scan_points,
                                                              const MeshDistance& reference_distance,
                                                              const std::vector<Eigen::Vector3d>& reference_points,
                                                              double bead_width_mm, double axis_step_mm,
                                                              CorrectionMethod method, int debug_level);

// Side-wall waviness of the undistorted twin part: scan points off the top and bottom faces are binned by their
// closest target point in cubes of `cell_mm` (about three layers) and each bin's peak-to-valley of the deviation is
// its W_t (DIN EN ISO 4287, as 003 sec. 6.4.1). The termination condition of 003 sec. 6.5.2 is the *maximum*
// waviness: part I's W_t "fluctuates, and limits to 1.22 mm" (sec. 6.6.3.1, Fig. 80), and the loop stops once "the
// surface deviation is within the maximum waviness". That is also the floor of the loop: a part built on a moved
// path lays its ripple elsewhere than the reference's, so their difference reaches the ripple's peak-to-valley.
// `max_mm` is the 99th percentile of the bins (so that a few odd bins do not set it), `median_mm` the typical bin.
struct Waviness {
  double median_mm = 0.0;
  double max_mm = 0.0;
};

// W_t over the bins of `cell_mm` (> 0; the loop uses 2 reference spacings, 4 mm) that hold at least 8 side-wall
// points of `scan`, mm; zero when no bin does.
Waviness WallWaviness(const ScanDeviation& scan, double cell_mm, int debug_level = 0);

// The loop's stop tolerance on max |deviation| (mm): `requested_mm` when > 0 (the user's tolerance), else the maximum waviness.
double StopTolerance(double requested_mm, const Waviness& waviness);

// Diagnostic only, never an input of the loop: the largest in-plane difference (mm) between the corrections `s` and
// the error the twin's hidden displacement `field` gives at each point of `current`, (r_i + u(r_i) - r0_i)_perp with
// r0_i the point of `nominal`, over the welded points where the field is defined. Printed per layer on stderr when
// debug_level >= 1 (every layer at 2).
double CorrectionError(const planner::Plan& nominal, const planner::Plan& current, const DistortionField& field,
                       const std::vector<std::vector<Eigen::Vector3d>>& s, int debug_level);

}  // namespace waam::twin::internal
