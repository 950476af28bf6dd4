// Scan deviation, central axis by adaptive slicing of a point cloud, caliper diameters and ovality (eq. 6.5).
#include "twin/scanner/scan_deviation.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/numbers.h"

namespace waam::twin {

namespace {

// min, max, the weighted mean and rms and max |d| of `r`'s deviations, in the points' order (the same on any number
// of threads).
void Summarize(ScanDeviation* r) {
  double sum = 0.0, sum2 = 0.0, total = 0.0;
  r->min_mm = std::numeric_limits<double>::infinity();
  r->max_mm = -r->min_mm;
  for (std::size_t i = 0; i < r->deviation_mm.size(); ++i) {
    const double d = r->deviation_mm[i], w = r->weight[i];
    sum += w * d;
    sum2 += w * d * d;
    total += w;
    r->min_mm = std::min(r->min_mm, d);
    r->max_mm = std::max(r->max_mm, d);
  }
  r->mean_mm = sum / total;
  r->rms_mm = std::sqrt(sum2 / total);
  r->max_abs_mm = std::max(std::abs(r->min_mm), std::abs(r->max_mm));
}

}  // namespace

ScanDeviation MeasureScanDeviation(const std::vector<Eigen::Vector3d>& scan, const MeshDistance& target,
                                   const std::vector<double>& weight) {
  WAAM_THROW_UNLESS(!scan.empty(), "deviation: the scan has no points");
  WAAM_THROW_UNLESS(weight.empty() || weight.size() == scan.size(),
                    "deviation: " << weight.size() << " weights for " << scan.size() << " points");
  ScanDeviation r;
  r.points = scan;
  r.weight = weight.empty() ? std::vector<double>(scan.size(), 1.0) : weight;
  for (std::size_t i = 0; i < r.weight.size(); ++i) {
    WAAM_THROW_UNLESS(r.weight[i] > 0.0 && std::isfinite(r.weight[i]),
                      "deviation: point " << i << " has weight " << r.weight[i] << ": must be > 0");
  }
  r.deviation_mm.resize(scan.size());
  r.normal.resize(scan.size());
  // Each point's distance and normal in parallel, into its own slot.
  constexpr std::size_t kChunk = 4096;
  ParallelFor((scan.size() + kChunk - 1) / kChunk, [&](std::size_t chunk) {
    const std::size_t end = std::min(scan.size(), (chunk + 1) * kChunk);
    for (std::size_t i = chunk * kChunk; i < end; ++i) {
      Eigen::Vector3d closest;
      const double d = target.SignedDistance(scan[i], &closest);
      r.deviation_mm[i] = d;
      const Eigen::Vector3d off = scan[i] - closest;
      // Outward normal at the closest point: along the offset, pointing outside (d > 0) or back out (d < 0).
      r.normal[i] = off.norm() > 1e-9 ? Eigen::Vector3d((d >= 0 ? 1.0 : -1.0) * off.normalized())
                                      : Eigen::Vector3d::Zero();
    }
  });
  Summarize(&r);
  return r;
}

ScanDeviation KeepScanPoints(const ScanDeviation& scan, const std::function<bool(std::size_t)>& keep) {
  ScanDeviation r;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    if (!keep(i)) continue;
    r.points.push_back(scan.points[i]);
    r.deviation_mm.push_back(scan.deviation_mm[i]);
    r.normal.push_back(scan.normal[i]);
    r.weight.push_back(scan.weight.empty() ? 1.0 : scan.weight[i]);
  }
  if (r.points.empty()) return ScanDeviation{};
  Summarize(&r);
  return r;
}

double AbsDeviationQuantile(const ScanDeviation& scan, double q) {
  WAAM_THROW_UNLESS(q >= 0.0 && q <= 1.0, "deviation quantile " << q << ": must be in [0, 1]");
  const std::size_t n = scan.deviation_mm.size();
  if (n == 0) return 0.0;
  auto weight = [&](std::size_t i) { return scan.weight.empty() ? 1.0 : scan.weight[i]; };
  std::vector<std::size_t> order(n);
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    order[i] = i;
    total += weight(i);
  }
  // Equal |d| cross the threshold together whatever their order, so the value does not depend on the sort's ties.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::abs(scan.deviation_mm[a]) < std::abs(scan.deviation_mm[b]);
  });
  double below = 0.0;
  for (const std::size_t i : order) {
    below += weight(i);
    if (below > q * total) return std::abs(scan.deviation_mm[i]);
  }
  return std::abs(scan.deviation_mm[order.back()]);
}

ScanDeviation ExcludeFacing(const ScanDeviation& scan, const Eigen::Vector3d& dir, double min_cos) {
  return KeepScanPoints(scan, [&](std::size_t i) { return scan.normal[i].dot(dir) <= min_cos; });
}

double Ovality(double d_max_mm, double d_min_mm) {
  return d_max_mm + d_min_mm > 0.0 ? 200.0 * (d_max_mm - d_min_mm) / (d_max_mm + d_min_mm) : 0.0;  // eq. 6.5
}

SectionMeasure MeasureSection(const std::vector<Eigen::Vector3d>& cloud, const AxisStation& station, double slab_mm,
                              double radius_mm) {
  SectionMeasure m;
  std::vector<Eigen::Vector3d> in;
  for (const Eigen::Vector3d& p : cloud) {
    const Eigen::Vector3d r = p - station.center;
    if (std::abs(r.dot(station.normal)) <= 0.5 * slab_mm && r.norm() <= radius_mm) in.push_back(p);
  }
  m.points = in.size();
  if (in.empty()) return m;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : in) mean += p;
  mean /= static_cast<double>(in.size());
  const Eigen::Vector3d t1 = station.normal.unitOrthogonal();
  const Eigen::Vector3d t2 = station.normal.cross(t1);
  m.d_min_mm = std::numeric_limits<double>::infinity();
  // The section centre is the centre of the caliper: c . e_k = (lo_k + hi_k) / 2 for the 36 directions in least
  // squares, so it does not depend on how densely each side was scanned (a rough wall exposes more points).
  Eigen::Matrix2d ata = Eigen::Matrix2d::Zero();
  Eigen::Vector2d atb = Eigen::Vector2d::Zero();
  for (int k = 0; k < 36; ++k) {
    const double a = k * kPi / 36.0;
    const Eigen::Vector3d e = std::cos(a) * t1 + std::sin(a) * t2;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Eigen::Vector3d& p : in) {
      lo = std::min(lo, p.dot(e));
      hi = std::max(hi, p.dot(e));
    }
    m.d_min_mm = std::min(m.d_min_mm, hi - lo);
    m.d_max_mm = std::max(m.d_max_mm, hi - lo);
    const Eigen::Vector2d e2(std::cos(a), std::sin(a));
    ata += e2 * e2.transpose();
    atb += e2 * (0.5 * (lo + hi) - mean.dot(e));
  }
  const Eigen::Vector2d c2 = ata.ldlt().solve(atb);
  m.centroid = mean + c2.x() * t1 + c2.y() * t2;
  m.ovality_pct = Ovality(m.d_max_mm, m.d_min_mm);
  return m;
}

std::vector<AxisStation> CentralAxis(const std::vector<Eigen::Vector3d>& surface, double step_mm, double slab_mm) {
  WAAM_THROW_UNLESS(step_mm > 0.0 && slab_mm > 0.0,
                    "central axis: step " << step_mm << " mm and slab " << slab_mm << " mm: must be > 0");
  std::vector<AxisStation> axis;
  if (surface.empty()) return axis;
  double z_min = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : surface) z_min = std::min(z_min, p.z());
  Eigen::Vector3d lo = surface[0], hi = surface[0];
  for (const Eigen::Vector3d& p : surface) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double extent = (hi - lo).norm();
  AxisStation station;
  station.center = Eigen::Vector3d(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), z_min + step_mm);
  station.normal = Eigen::Vector3d::UnitZ();
  double reach = 2.0 * extent;   // limited to 1.5 x the first section's radius once it is known
  const int max_stations = static_cast<int>(std::ceil(4.0 * extent / step_mm)) + 2;
  for (int i = 0; i < max_stations; ++i) {
    SectionMeasure m = MeasureSection(surface, station, slab_mm, reach);
    if (m.points < 8) break;
    AxisStation s = station;
    s.center = m.centroid;
    for (const Eigen::Vector3d& p : surface) {
      const Eigen::Vector3d r = p - station.center;
      if (std::abs(r.dot(station.normal)) <= 0.5 * slab_mm && r.norm() <= reach) {
        s.radius_mm = std::max(s.radius_mm, (p - m.centroid).norm());
      }
    }
    if (!axis.empty()) {
      const Eigen::Vector3d d = s.center - axis.back().center;
      if (d.norm() < 1e-6) break;
      // Past the end the slab catches a partial ring whose centre runs off: stop when the plane would turn by more
      // than 30 degrees in one step or the section grows by a quarter over the first.
      if (d.normalized().dot(axis.back().normal) < 0.866 || s.radius_mm > 1.25 * axis.front().radius_mm) break;
      s.normal = d.normalized();   // the plane turns perpendicular to I_i I_{i+1}
      s.s_mm = axis.back().s_mm + d.norm();
    } else {
      reach = 1.5 * s.radius_mm + slab_mm;
    }
    axis.push_back(s);
    station.center = s.center + step_mm * s.normal;   // G = I_i + h' N
    station.normal = s.normal;
  }
  return axis;
}

AxisComparison CompareAxis(const std::vector<Eigen::Vector3d>& target_surface,
                           const std::vector<Eigen::Vector3d>& scan, double step_mm, double slab_mm) {
  AxisComparison c;
  c.stations = CentralAxis(target_surface, step_mm, slab_mm);
  double reach = 0.0;
  for (const AxisStation& s : c.stations) reach = std::max(reach, 1.5 * s.radius_mm + slab_mm);
  for (std::size_t i = 0; i < c.stations.size(); ++i) {
    const AxisStation& s = c.stations[i];
    const SectionMeasure m = MeasureSection(scan, s, slab_mm, 1.5 * s.radius_mm + 2.0 * slab_mm + 5.0);
    const SectionMeasure t = MeasureSection(target_surface, s, slab_mm, 1.5 * s.radius_mm + 2.0 * slab_mm + 5.0);
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    // Only complete sections count: near the ends of a tilted or shifted part the slab cuts a partial ring whose
    // caliper centre is not the axis.
    // Within half a section radius (at most 15 % of the axis) of either end the slab cuts the end cap or a plane that is still turning.
    const double margin = std::min(0.5 * s.radius_mm, 0.15 * c.stations.back().s_mm);
    const bool end = s.s_mm < margin || s.s_mm > c.stations.back().s_mm - margin;
    const bool complete = !end && m.points > 0 && m.d_min_mm >= 0.8 * t.d_min_mm && m.d_max_mm >= 0.8 * t.d_max_mm &&
                          m.d_max_mm <= 1.25 * t.d_max_mm;
    if (complete) {
      d = m.centroid - s.center;
      d -= d.dot(s.normal) * s.normal;
    }
    c.deviation.push_back(d);
    c.max_axis_deviation_mm = std::max(c.max_axis_deviation_mm, d.norm());
  }
  if (!c.stations.empty()) {
    // The three cuts of Fig. 69, a little inside the ends so the slab is full.
    const std::size_t n = c.stations.size();
    const std::size_t idx[3] = {std::min<std::size_t>(1, n - 1), n / 2, n >= 2 ? n - 2 : 0};
    SectionMeasure* target[3] = {&c.target_bottom, &c.target_middle, &c.target_top};
    SectionMeasure* scanned[3] = {&c.scan_bottom, &c.scan_middle, &c.scan_top};
    for (int k = 0; k < 3; ++k) {
      const AxisStation& s = c.stations[idx[k]];
      const double r = 1.5 * s.radius_mm + 2.0 * slab_mm + 5.0;
      *target[k] = MeasureSection(target_surface, s, slab_mm, r);
      *scanned[k] = MeasureSection(scan, s, slab_mm, r);
    }
  }
  return c;
}

}  // namespace waam::twin
