// The compensation loop of 003 sec. 6.5.2 in the twin. Each reference point r_i of the tool path (2 mm apart) is
// moved against the deviation S_i the scan shows around it: r*_i = r_i - S_i.
//
// S_i is estimated from the scan alone, so a real scan works the same way (compensation_corrections.cc): the central
// axis of the scan is compared with the reference axis section by section and bent back against its offset, and the
// cross sections are corrected point by point from the closest-point deviations of the scan moved back onto the
// reference axis. Only the component in the layer plane moves the point. Like the dissertation (which corrects the
// cross sections and the axis), the build-direction shrinkage is not compensated: the top end (the scan points whose
// reference point lies within two bead heights plus the measured shortening of the planned top, along the last
// layer's build direction) is left out of the deviation measures.
#include "twin/compensation/compensation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <limits>
#include <memory>
#include <optional>
#include <unordered_map>

#include "models/core/error.h"
#include "models/core/progress.h"
#include "twin/deposition/bead_deposition.h"
#include "twin/distortion/deposit_history.h"
#include "twin/scanner/mesh_distance.h"
#include "twin/scanner/point_hash.h"
#include "twin/scanner/surface_sample.h"
#include "twin/scanner/surface_mesh.h"
#include "twin/compensation/compensation_internal.h"

namespace waam::twin {
namespace {

// Deviation statistics, the central-axis offset against the reference's axis (the same reference as the deviations:
// the undistorted twin part or the target) and the ovality (eq. 6.5) of the highest complete scan section (the top
// cut of Fig. 69; the shortened top end cuts partial rings).
void Summarize(const ScanDeviation& scan, const std::vector<Eigen::Vector3d>& reference_points, double axis_step_mm,
               CompensationIteration* it) {
  it->max_abs_deviation_mm = scan.max_abs_mm;
  it->rms_deviation_mm = scan.rms_mm;
  // Per unit area for a real STL scan (its points carry their areas), per point for the twin's equal voxel faces.
  it->p99_abs_deviation_mm = AbsDeviationQuantile(scan, 0.99);
  it->min_deviation_mm = scan.min_mm;
  it->max_deviation_mm = scan.max_mm;
  const AxisComparison axis = CompareAxis(reference_points, scan.points, axis_step_mm, 0.5 * axis_step_mm);
  it->axis_deviation_mm = axis.max_axis_deviation_mm;
  it->ovality_pct = axis.scan_top.ovality_pct;
  for (std::size_t i = axis.stations.size(); i-- > 0;) {
    if (axis.deviation[i].squaredNorm() > 0.0) {
      const AxisStation& s = axis.stations[i];
      it->ovality_pct = MeasureSection(scan.points, s, 0.5 * axis_step_mm, 1.5 * s.radius_mm + axis_step_mm + 5.0).ovality_pct;
      break;
    }
  }
}

// `scan` without the points whose closest reference point lies within `band_mm` of the top end (`top`, the largest
// coordinate of the planned path along the unit `dir`), statistics recomputed. The rim of the last layers shows the
// build-direction shrinkage, which the in-plane path correction does not address (003 makes it up by bead height).
// A point is in the band when it or its closest reference point is: a rim that bulges out over the band's edge (the
// last layers, whose sections the scan cannot measure whole) is the rim, not the wall below it.
ScanDeviation ExcludeTopBand(const ScanDeviation& scan, const Eigen::Vector3d& dir, double top, double band_mm) {
  return KeepScanPoints(scan, [&](std::size_t i) {
    const Eigen::Vector3d closest = scan.points[i] - scan.deviation_mm[i] * scan.normal[i];
    return closest.dot(dir) <= top - band_mm && scan.points[i].dot(dir) <= top - band_mm;
  });
}

// The top of `points` along the unit `dir`, mm: the 99.5th percentile, so that a few stray voxels (a spatter-like
// spike of the deposit) do not set it.
double TopOf(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& dir) {
  if (points.empty()) return 0.0;
  std::vector<double> h(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) h[i] = points[i].dot(dir);
  const std::size_t k = std::min(h.size() - 1, static_cast<std::size_t>(0.995 * static_cast<double>(h.size())));
  std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(k), h.end());
  return h[k];
}

// The highest weld point of the path along the unit `dir`, mm (not the retract above the last pass).
double PathTop(const planner::Plan& plan, const Eigen::Vector3d& dir) {
  double top = -std::numeric_limits<double>::infinity();
  for (const planner::LayerPath& layer : plan.layers) {
    for (const planner::PathPoint& p : layer.points) {
      if (p.weld) top = std::max(top, p.p_P.dot(dir));
    }
  }
  return top;
}

}  // namespace

namespace internal {

// W_t of each bin: the peak-to-valley of the deviation (DIN EN ISO 4287, as 003 sec. 6.4.1).
Waviness WallWaviness(const ScanDeviation& scan, double cell_mm, int debug_level) {
  std::unordered_map<std::uint64_t, std::pair<double, double>> bins;
  std::unordered_map<std::uint64_t, int> counts;
  double z_lo = std::numeric_limits<double>::infinity(), z_hi = -z_lo;
  for (const Eigen::Vector3d& p : scan.points) {
    z_lo = std::min(z_lo, p.z());
    z_hi = std::max(z_hi, p.z());
  }
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    if (std::abs(scan.normal[i].z()) > 0.5) continue;  // top and bottom faces
    const Eigen::Vector3d closest = scan.points[i] - scan.deviation_mm[i] * scan.normal[i];
    if (closest.z() < z_lo + cell_mm || closest.z() > z_hi - cell_mm) continue;
    const Eigen::Vector3i c = CellOf(closest, cell_mm);
    // Separate the faces of a thin wall by the side they look to.
    const int side = (scan.normal[i].x() > 0 ? 1 : 0) + (scan.normal[i].y() > 0 ? 2 : 0);
    const std::uint64_t key = (static_cast<std::uint64_t>(c.x() + (1 << 19)) & 0xFFFFF) |
                              ((static_cast<std::uint64_t>(c.y() + (1 << 19)) & 0xFFFFF) << 20) |
                              ((static_cast<std::uint64_t>(c.z() + (1 << 19)) & 0xFFFFF) << 40) |
                              (static_cast<std::uint64_t>(side) << 60);
    auto [it, inserted] = bins.try_emplace(key, scan.deviation_mm[i], scan.deviation_mm[i]);
    it->second.first = std::min(it->second.first, scan.deviation_mm[i]);
    it->second.second = std::max(it->second.second, scan.deviation_mm[i]);
    ++counts[key];
  }
  std::vector<double> p2v;
  for (const auto& [key, range] : bins) {
    if (counts[key] >= 8) p2v.push_back(range.second - range.first);
  }
  if (p2v.empty()) return {};
  std::sort(p2v.begin(), p2v.end());
  auto at = [&](double q) { return p2v[std::min(p2v.size() - 1, static_cast<std::size_t>(q * p2v.size()))]; };
  if (debug_level >= 1) {
    std::fprintf(stderr, "waviness: %zu cells, p2v median %.3f p90 %.3f p95 %.3f p99 %.3f p99.9 %.3f max %.3f mm\n",
                 p2v.size(), at(0.5), at(0.9), at(0.95), at(0.99), at(0.999), p2v.back());
  }
  return {at(0.5), at(0.99)};
}

// 003 sec. 6.5.2: the loop stops "whenever the surface deviation is within the maximum waviness".
double StopTolerance(double requested_mm, const Waviness& waviness) {
  return requested_mm > 0.0 ? requested_mm : waviness.max_mm;
}

}  // namespace internal

planner::Plan ResamplePlan(const planner::Plan& plan, double spacing_mm) {
  WAAM_THROW_UNLESS(spacing_mm > 0.0, "compensation reference spacing " << spacing_mm << " mm: must be > 0");
  planner::Plan out = plan;
  for (planner::LayerPath& layer : out.layers) {
    std::vector<planner::PathPoint> points;
    for (std::size_t i = 0; i < layer.points.size(); ++i) {
      const planner::PathPoint& p = layer.points[i];
      if (i > 0 && p.weld) {
        const planner::PathPoint& a = layer.points[i - 1];
        const int n = static_cast<int>(std::ceil((p.p_P - a.p_P).norm() / spacing_mm));
        for (int k = 1; k < n; ++k) {
          planner::PathPoint q = p;
          q.p_P = a.p_P + (p.p_P - a.p_P) * (static_cast<double>(k) / n);
          points.push_back(q);
        }
      }
      points.push_back(p);
    }
    layer.points = std::move(points);
  }
  return out;
}

std::vector<Eigen::Vector3d> ScanDistortedPart(const VoxelGrid& grid, const DistortionField& field) {
  std::vector<Eigen::Vector3d> points;
  VoxelIndex lo, hi;
  if (!grid.Bounds(&lo, &hi)) return points;
  // Air: the empty voxels of the bounding box (one voxel larger, above the substrate) that the outside reaches
  // (6-connected flood fill). Faces towards enclosed voids are not seen by a scanner.
  lo -= VoxelIndex::Ones();
  hi += VoxelIndex::Ones();
  lo.z() = 0;
  const Eigen::Vector3i size = hi - lo + VoxelIndex::Ones();
  const std::size_t total = static_cast<std::size_t>(size.x()) * size.y() * size.z();
  auto offset = [&](const VoxelIndex& v) {
    return (static_cast<std::size_t>(v.z() - lo.z()) * size.y() + (v.y() - lo.y())) * size.x() + (v.x() - lo.x());
  };
  auto inside = [&](const VoxelIndex& v) { return (v.array() >= lo.array()).all() && (v.array() <= hi.array()).all(); };
  std::vector<std::uint8_t> air(total, 0);
  // Breadth first: the queue holds the front of the fill (about the box's surface), where a depth-first stack grows to
  // a large part of the air (part II: 88 M voxels in the box, 0.5-0.8 GB of stack). Same air either way.
  std::deque<VoxelIndex> queue;
  const Eigen::Vector3i dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  // A laser line scanner does not see into one-voxel slots (seams between bead rasters): an empty voxel with metal on
  // both sides along an axis is not air the scanner reaches.
  auto slot = [&](const VoxelIndex& v) {
    for (int a = 0; a < 3; ++a) {
      if (grid.Occupied(v + VoxelIndex::Unit(a)) && grid.Occupied(v - VoxelIndex::Unit(a))) return true;
    }
    return false;
  };
  auto seed = [&](const VoxelIndex& v) {
    if (!grid.Occupied(v) && !air[offset(v)] && !slot(v)) {
      air[offset(v)] = 1;
      queue.push_back(v);
    }
  };
  for (int z = lo.z(); z <= hi.z(); ++z) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      seed(VoxelIndex(lo.x(), y, z));
      seed(VoxelIndex(hi.x(), y, z));
    }
    for (int x = lo.x(); x <= hi.x(); ++x) {
      seed(VoxelIndex(x, lo.y(), z));
      seed(VoxelIndex(x, hi.y(), z));
    }
  }
  for (int y = lo.y(); y <= hi.y(); ++y) {
    for (int x = lo.x(); x <= hi.x(); ++x) seed(VoxelIndex(x, y, hi.z()));
  }
  while (!queue.empty()) {
    const VoxelIndex v = queue.front();
    queue.pop_front();
    for (const Eigen::Vector3i& d : dirs) {
      const VoxelIndex n = v + d;
      if (inside(n)) seed(n);
    }
  }
  const double s = grid.voxel_mm();
  grid.ForEach([&](const VoxelIndex& idx, const VoxelData&) {
    for (const Eigen::Vector3i& d : dirs) {
      const VoxelIndex n = idx + d;
      if (n.z() < 0 || !inside(n) || !air[offset(n)]) continue;
      const Eigen::Vector3d p = grid.Center(idx) + 0.5 * s * d.cast<double>();
      points.push_back(p + field.Displacement(p));
    }
  });
  // Radius outlier removal, as the scanner's software does: a face sample needs 8 others within two voxels. A
  // surface keeps every sample (about 12 within that radius on a flat face, 9 on a wall's edge); a lone voxel (6
  // faces, 5 neighbours each) is dropped. After two compensations of part IV the max |deviation| (7.06 mm) was set by
  // such specks: single voxels, no other sample within 1.5 mm, 5-7 mm off the surface.
  const std::vector<std::size_t> keep = DenseScanPoints(points, 2.0 * s, 8);
  if (keep.size() == points.size()) return points;
  std::vector<Eigen::Vector3d> dense;
  dense.reserve(keep.size());
  for (std::size_t i : keep) dense.push_back(points[i]);
  return dense;
}

namespace {

// Throws InputError for options out of range, a target without facets or invalid distortion settings.
void ValidateCompensation(const planner::TriangleMesh& target, const CompensationOptions& options) {
  WAAM_THROW_UNLESS(options.max_iterations >= 0 && options.max_iterations <= 20,
                    "compensation max_iterations = " << options.max_iterations << ": must be in [0, 20]");
  WAAM_THROW_UNLESS(options.tolerance_mm >= 0.0, "compensation tolerance_mm = " << options.tolerance_mm << ": must be >= 0");
  WAAM_THROW_UNLESS(!target.facets.empty(), "compensate: the target part has no facets");
  ValidateDistortionOptions(options.distortion);
  models::ValidateDistortionParams(options.params, "distortion model");
}

// The top rim left out of the measures, mm: two mean bead heights of the last layer (0 without one).
double TopBand(const planner::Plan& nominal) {
  if (nominal.layers.empty()) return 0.0;
  double sum = 0.0;
  for (const planner::PathPoint& p : nominal.layers.back().points) sum += p.bead_height_mm;
  return nominal.layers.back().points.empty() ? 0.0 : 2.0 * sum / nominal.layers.back().points.size();
}

// r*_i = r_i - S_i: moves every point of `current` by minus its correction `s` (per layer, per point, mm); returns
// the largest correction, mm.
double ApplyCorrections(const std::vector<std::vector<Eigen::Vector3d>>& s, planner::Plan* current) {
  double largest = 0.0;
  for (std::size_t l = 0; l < current->layers.size(); ++l) {
    for (std::size_t i = 0; i < current->layers[l].points.size(); ++i) {
      current->layers[l].points[i].p_P -= s[l][i];
      largest = std::max(largest, s[l][i].norm());
    }
  }
  return largest;
}

// The loop's status after iteration `iter` (the last of result->iterations): converged, diverging (from
// `previous`, mm) or out of iterations, with its message; nothing while the loop goes on.
void SetStatus(int iter, bool done, bool diverging, double previous, int max_iterations, CompensationResult* result) {
  const CompensationIteration& it = result->iterations.back();
  if (done) {
    result->converged = true;
    result->status = "converged";
    result->message = "converged: max |deviation| " + std::to_string(it.max_abs_deviation_mm) + " mm < tolerance " +
                      std::to_string(result->tolerance_mm) + " mm after " + std::to_string(iter) + " compensation(s)";
  } else if (diverging) {
    result->status = "diverging";
    result->message = "cannot converge: max |deviation| went from " + std::to_string(previous) + " to " +
                      std::to_string(it.max_abs_deviation_mm) + " mm (tolerance " +
                      std::to_string(result->tolerance_mm) + " mm); the loop stops instead of repeating";
  } else if (iter == max_iterations) {
    result->status = "max_iterations";
    result->message = "not converged after " + std::to_string(iter) + " compensation(s): max |deviation| " +
                      std::to_string(it.max_abs_deviation_mm) + " mm >= tolerance " +
                      std::to_string(result->tolerance_mm) + " mm";
  }
}

// The loop's state across iterations: the nominal path, the reference the part is driven to, the current path
// and the result so far.
class CompensationLoop {
 public:
  CompensationLoop(const planner::Plan& plan, const planner::TriangleMesh& target,
                   const twin::SimulationSettings& settings, const CompensationOptions& options);
  // Iteration `iter`: builds and scans the current path, measures it and corrects the path unless the loop stops.
  // Returns true when it stops (converged or diverging).
  bool Iterate(int iter, const std::function<void(int, const CompensationIteration&)>& on_iteration);
  // The result, with the last corrected path.
  CompensationResult Finish();

 private:
  // A scan of the built part: the twin's (with the distortion field that made it) or the real first scan.
  struct PartScan {
    std::vector<Eigen::Vector3d> points;
    std::vector<double> weights;  // the real first scan's; the twin's scans weigh every point alike
    DistortionField field;
    bool simulated = true;
  };
  PartScan BuildAndScan(int iter, CompensationIteration& it);
  void SetReference(const Depositor& depositor);
  ScanDeviation Measure(const PartScan& scan, CompensationIteration& it) const;
  void Correct(const PartScan& scan, const ScanDeviation& deviation, CompensationIteration& it);

  const twin::SimulationSettings& settings_;
  const CompensationOptions& options_;
  const planner::Plan nominal_;
  const MeshDistance distance_;
  const std::vector<Eigen::Vector3d> target_surface_;
  const bool shaped_;
  const bool twin_reference_;
  planner::TriangleMesh reference_mesh_;
  std::unique_ptr<MeshDistance> reference_;
  std::vector<Eigen::Vector3d> reference_points_;
  planner::Plan current_;
  CompensationResult result_;
};

// The reference the loop drives the part to. "twin": the nominal path deposited without distortion (what the process
// makes of the target; bead-shape errors no path shift can fix, such as arc starts and corners, are left out).
// "target": the target mesh itself, as 003 compares scans with the CAD model (always so with a real scan).
CompensationLoop::CompensationLoop(const planner::Plan& plan, const planner::TriangleMesh& target,
                                   const twin::SimulationSettings& settings, const CompensationOptions& options)
    : settings_(settings), options_(options), nominal_(ResamplePlan(plan, options.reference_spacing_mm)),
      distance_(target), target_surface_(SampleSurface(target, 0.5 * options.axis_step_mm)),
      shaped_(!options.bead_heat.height.empty()),
      twin_reference_(options.reference == CompensationReference::kTwin && options.first_scan.empty()),
      reference_points_(target_surface_), current_(nominal_) {
  result_.reference = twin_reference_ ? CompensationReference::kTwin : CompensationReference::kTarget;
  // The top rim left out of the measures: two bead heights of the last layer (plus each scan's shortening).
  result_.top_band_mm = TopBand(nominal_);
}

// The reference and the tolerance, from the nominal path with its planned beads (`depositor`: the first build).
void CompensationLoop::SetReference(const Depositor& depositor) {
  std::optional<Depositor> planned;
  if (shaped_) planned.emplace(DepositPlan(current_, settings_, options_.rapid_speed_mm_s, nullptr));
  const Depositor& nominal_deposit = shaped_ ? *planned : depositor;
  const ScanDeviation undistorted =
      MeasureScanDeviation(ScanDistortedPart(nominal_deposit.grid(), DistortionField()), distance_);
  const internal::Waviness waviness =
      internal::WallWaviness(undistorted, 2.0 * options_.reference_spacing_mm, options_.debug_level);
  result_.waviness_mm = waviness.max_mm;
  result_.waviness_median_mm = waviness.median_mm;
  result_.tolerance_mm = internal::StopTolerance(options_.tolerance_mm, waviness);
  if (twin_reference_) {
    reference_mesh_ = ExtractSurface(nominal_deposit.grid());
    reference_ = std::make_unique<MeshDistance>(reference_mesh_);
    reference_points_ = undistorted.points;
  }
}

// What the build lays: the path's beads, shaped by the heat where they are laid when a thermal history is given;
// scanned after its distortion, or the real first scan at iteration 0 when one is given.
CompensationLoop::PartScan CompensationLoop::BuildAndScan(int iter, CompensationIteration& it) {
  PartScan scan;
  const planner::Plan built = shaped_ ? ShapeBeadsByHeat(current_, options_.bead_heat) : planner::Plan{};
  const planner::Plan& laid = shaped_ ? built : current_;
  const Depositor depositor = DepositPlan(laid, settings_, options_.rapid_speed_mm_s, nullptr);
  if (iter == 0) {
    SetReference(depositor);
    if (!options_.first_scan.empty()) {
      it.real_scan = true;
      scan.simulated = false;
      scan.points = options_.first_scan;
      scan.weights = options_.first_scan_weight;
      return scan;
    }
  }
  const DepositHistory history(laid, depositor, settings_, options_.rapid_speed_mm_s, options_.wire_feed_mm_s);
  scan.field = ComputeDistortion(depositor.grid(), history, options_.params, options_.distortion, &it.distortion);
  scan.points = ScanDistortedPart(depositor.grid(), scan.field);
  return scan;
}

// The scan's deviation from the reference (and from the target, in `it`) without the top end: the end face and the
// rim below it (a band along the last layer's build direction, not a normal cone: the side walls of a bent tube's
// first layers face the last layer's build direction too).
ScanDeviation CompensationLoop::Measure(const PartScan& scan, CompensationIteration& it) const {
  const Eigen::Vector3d top_dir = nominal_.layers.empty()
                                      ? Eigen::Vector3d::UnitZ()
                                      : Eigen::Vector3d(nominal_.layers.back().build_dir_P.normalized());
  const double path_top = PathTop(nominal_, top_dir);
  // The rim: two bead heights plus the shortening the scan shows at the top end (its highest point below the
  // reference's along the build direction).
  const double shortening = std::max(
      0.0, TopOf(twin_reference_ ? reference_points_ : target_surface_, top_dir) - TopOf(scan.points, top_dir));
  it.top_band_mm = result_.top_band_mm + shortening;
  if (options_.debug_level >= 1) {
    std::fprintf(stderr, "top: dir (%.3f %.3f %.3f), path top %.2f mm, band %.2f mm (shortening %.2f mm)\n",
                 top_dir.x(), top_dir.y(), top_dir.z(), path_top, it.top_band_mm, shortening);
  }
  const ScanDeviation against_target = ExcludeTopBand(MeasureScanDeviation(scan.points, distance_, scan.weights),
                                                      top_dir, path_top, it.top_band_mm);
  it.max_abs_vs_target_mm = against_target.max_abs_mm;
  it.rms_vs_target_mm = against_target.rms_mm;
  ScanDeviation deviation =
      twin_reference_ ? ExcludeTopBand(MeasureScanDeviation(scan.points, *reference_, scan.weights), top_dir,
                                       path_top, it.top_band_mm)
                      : against_target;
  Summarize(deviation, reference_points_, options_.axis_step_mm, &it);
  return deviation;
}

// r*_i = r_i - S_i on the current path; S from the scan around the nominal point.
void CompensationLoop::Correct(const PartScan& scan, const ScanDeviation& deviation, CompensationIteration& it) {
  const MeshDistance& reference_distance = twin_reference_ ? *reference_ : distance_;
  const std::vector<std::vector<Eigen::Vector3d>> s = internal::EstimateCorrections(
      nominal_, deviation, scan.points, reference_distance, reference_points_, options_.bead_width_mm,
      options_.axis_step_mm, options_.correction, options_.debug_level);
  if (scan.simulated) {
    it.twin_correction_error_mm = internal::CorrectionError(nominal_, current_, scan.field, s, options_.debug_level);
  }
  it.max_correction_mm = ApplyCorrections(s, &current_);
}

bool CompensationLoop::Iterate(int iter, const std::function<void(int, const CompensationIteration&)>& on_iteration) {
  CheckInterrupt();
  result_.last_scan = ScanDeviation{};  // the previous build's, replaced below: not kept through this build
  CompensationIteration it;
  const PartScan scan = BuildAndScan(iter, it);
  ScanDeviation deviation = Measure(scan, it);
  if (iter == 0) {
    WAAM_THROW_UNLESS(result_.tolerance_mm > 0.0,
                      "compensation: the simulated part has no measurable waviness (first scan given?); give a tolerance");
    result_.first_scan = deviation;
  }
  const bool done = it.max_abs_deviation_mm < result_.tolerance_mm;
  const double previous = result_.iterations.empty() ? std::numeric_limits<double>::infinity()
                                                     : result_.iterations.back().max_abs_deviation_mm;
  const bool diverging = iter > 0 && it.max_abs_deviation_mm > 0.95 * previous;
  if (!done && !diverging && iter < options_.max_iterations) Correct(scan, deviation, it);
  result_.last_scan = std::move(deviation);
  result_.iterations.push_back(it);
  if (on_iteration) on_iteration(iter, it);
  SetStatus(iter, done, diverging, previous, options_.max_iterations, &result_);
  return done || diverging;
}

CompensationResult CompensationLoop::Finish() {
  result_.plan = current_;
  return std::move(result_);
}

}  // namespace

CompensationResult Compensate(const planner::Plan& plan, const planner::TriangleMesh& target,
                              const twin::SimulationSettings& settings, const CompensationOptions& options,
                              const std::function<void(int, const CompensationIteration&)>& on_iteration) {
  ValidateCompensation(target, options);
  CompensationLoop loop(plan, target, settings, options);
  for (int iter = 0; iter <= options.max_iterations; ++iter) {
    if (loop.Iterate(iter, on_iteration)) break;
  }
  return loop.Finish();
}

}  // namespace waam::twin
