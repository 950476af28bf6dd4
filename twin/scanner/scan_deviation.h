// Scan-to-target comparison of a point cloud: signed deviation per point, the central axis and the cross-section
// ovality (dissertation 003 sec. 6.4.2, eq. 6.5).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "twin/scanner/mesh_distance.h"

namespace waam::twin {

// Signed deviation of every scan point from the target (both in the part frame, mm).
struct ScanDeviation {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> deviation_mm;        // + outside the target (excess), - inside (shortfall)
  std::vector<Eigen::Vector3d> normal;     // unit outward normal of the target at the closest point
  std::vector<double> weight;              // what each point counts for in mean_mm and rms_mm: 1 per point of a
                                           // point cloud, the surface area (mm^2) it stands for on a sampled STL
  double min_mm = 0.0;
  double max_mm = 0.0;
  double mean_mm = 0.0;
  double rms_mm = 0.0;
  double max_abs_mm = 0.0;
};

// Measures every point of `scan` against `target`. mean_mm and rms_mm are weighted by `weight` (one per point, > 0;
// empty: 1 each). Throws InputError for an empty scan or a weight count that is not the point count.
ScanDeviation MeasureScanDeviation(const std::vector<Eigen::Vector3d>& scan, const MeshDistance& target,
                                   const std::vector<double>& weight = {});

// The q-quantile (0 <= q <= 1) of |deviation| over `scan`, each point counting by its weight (its area on a sampled
// STL, so the figure is per unit area as mean_mm and rms_mm are): the smallest |d| such that the points with |d| at
// or below it hold more than q of the total weight (the largest |d| if none does). With equal weights it is the
// element floor(q n) of the sorted |d|. 0 for a scan without points. Throws InputError for q outside [0, 1].
double AbsDeviationQuantile(const ScanDeviation& scan, double q);

// The points of `scan` whose target normal is NOT within acos(`min_cos`) of the unit `dir` (e.g. without the top
// end face), with the statistics recomputed; empty if none is left.
ScanDeviation ExcludeFacing(const ScanDeviation& scan, const Eigen::Vector3d& dir, double min_cos);

// `scan` with only the points i for which `keep(i)` is true, statistics recomputed (empty if none is kept).
ScanDeviation KeepScanPoints(const ScanDeviation& scan, const std::function<bool(std::size_t)>& keep);

// One station of a central axis: the section centroid and the section plane normal (unit, along the axis).
struct AxisStation {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double s_mm = 0.0;        // arc length along the axis from the first station, mm
  double radius_mm = 0.0;   // largest distance of a section point from the centroid, mm
};

// The central axis of the surface points `surface` by the adaptive slicing of 003 sec. 6.3.1 (Fig. 61): start
// with the plane z = z_min + step normal to z, take the centroid I_i of the points in a slab of `slab_mm` around the
// plane (within 1.5 x the first section's radius of it), move G = I_i + step N, and turn the plane normal to
// I_i I_{i+1}; stop when a slab is empty. `step_mm` and `slab_mm` > 0.
std::vector<AxisStation> CentralAxis(const std::vector<Eigen::Vector3d>& surface, double step_mm, double slab_mm);

// A cross section of a point cloud at one station.
struct SectionMeasure {
  std::size_t points = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // caliper centre of the section (mean along the normal)
  double d_min_mm = 0.0;      // smallest caliper diameter over 36 directions in the plane, mm
  double d_max_mm = 0.0;      // largest, mm
  double ovality_pct = 0.0;   // eq. 6.5: OV = 200 (d_max - d_min) / (d_max + d_min)
};

// Points of `cloud` within `slab_mm` / 2 of the station plane and within `radius_mm` of its centre.
SectionMeasure MeasureSection(const std::vector<Eigen::Vector3d>& cloud, const AxisStation& station, double slab_mm,
                              double radius_mm);

// The scan's central axis and sections measured at the target's stations.
struct AxisComparison {
  std::vector<AxisStation> stations;        // target axis
  std::vector<Eigen::Vector3d> deviation;   // scan centroid - target centroid, in the section plane, mm (0 if empty)
  double max_axis_deviation_mm = 0.0;
  SectionMeasure target_bottom, target_middle, target_top;
  SectionMeasure scan_bottom, scan_middle, scan_top;   // the three cuts of 003 Fig. 69
};

// Compares `scan` with the target surface samples `target_surface` along the target's central axis.
AxisComparison CompareAxis(const std::vector<Eigen::Vector3d>& target_surface,
                           const std::vector<Eigen::Vector3d>& scan, double step_mm, double slab_mm);

// Ovality of eq. 6.5 from two diameters (> 0), percent.
double Ovality(double d_max_mm, double d_min_mm);

}  // namespace waam::twin
