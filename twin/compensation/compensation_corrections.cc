// The corrections S_i of 003 sec. 6.5.2 from a scan alone: the central axis bent back against its measured offset,
// and the cross sections corrected point by point (r*_i = r_i - S_i).
//
// Why the axis first: a closest-point deviation only sees how far a surface point is from the nearest reference
// surface. Once a thin wall (part I: 4 mm) has moved sideways by more than about half its thickness, its inner face
// is nearest to the reference's outer face and the deviation no longer measures the move; the per-point mean of
// d_j n_j then saturates near the wall thickness and the loop stalls. The section centres of the scan (the caliper
// centre of each cut, 003 sec. 6.3.1 / 6.4.2) measure the axis offset at any size, because they do not pair points.
// So the scan is first moved back by the axis offset of its section, the remaining (small) closest-point deviations
// give the cross-section correction, and S_i is the sum.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include <Eigen/Geometry>

#include "models/core/numbers.h"
#include "models/core/parallel.h"
#include "twin/compensation/compensation_internal.h"
#include "twin/scanner/point_hash.h"

namespace waam::twin::internal {
namespace {

// Per-point in-plane correction: the mean of d_j n_j over the scan points near each nominal point in its layer band.
// A wall moved sideways by s shows +s on one face and -s on the other, both along the move, so the mean is the move;
// a wall that only got thicker cancels.
std::vector<std::vector<Eigen::Vector3d>> LocalCorrections(const planner::Plan& nominal, const ScanDeviation& scan,
                                                           double bead_width_mm) {
  const double radius = 0.5 * bead_width_mm + std::min(scan.max_abs_mm, 20.0) + 1.0;
  const PointHash hash(scan.points, radius);
  std::vector<std::vector<Eigen::Vector3d>> s(nominal.layers.size());
  // Each layer's corrections depend only on the scan: the layers run in parallel, each into its own slot.
  ParallelFor(nominal.layers.size(), [&](std::size_t l) {
    const planner::LayerPath& layer = nominal.layers[l];
    const Eigen::Vector3d n = layer.build_dir_P.normalized();
    s[l].assign(layer.points.size(), Eigen::Vector3d::Zero());
    std::vector<std::uint8_t> known(layer.points.size(), 0);
    for (std::size_t i = 0; i < layer.points.size(); ++i) {
      const planner::PathPoint& p = layer.points[i];
      const double band = std::max(p.bead_height_mm, 1.0);
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      int count = 0;
      hash.ForEachNear(p.p_P, radius, [&](int j) {
        if (std::abs((scan.points[j] - p.p_P).dot(n)) > band) return;
        // Side walls only: the rounded top rim of a shortened wall faces partly up and its deviation is height loss.
        if (std::abs(scan.normal[j].dot(n)) > 0.5) return;
        sum += scan.deviation_mm[j] * scan.normal[j];
        ++count;
      });
      if (count > 0) {
        const Eigen::Vector3d v = sum / count;
        s[l][i] = v - v.dot(n) * n;
        known[i] = 1;
      }
    }
    // Points with no scan near them (inside a solid layer) take the correction of the nearest known point.
    for (std::size_t i = 0; i < layer.points.size(); ++i) {
      if (known[i]) continue;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < layer.points.size(); ++k) {
        if (!known[k]) continue;
        const double d = (layer.points[k].p_P - layer.points[i].p_P).squaredNorm();
        if (d < best) {
          best = d;
          s[l][i] = s[l][k];
        }
      }
    }
  });
  return s;
}

}  // namespace

namespace {

// In-plane unit direction from the centre of `station` to `p` and its angle from `t1` (unit, in the plane), rad.
bool PlaneDirection(const AxisStation& station, const Eigen::Vector3d& t1, const Eigen::Vector3d& p,
                    Eigen::Vector3d* e, double* angle) {
  Eigen::Vector3d r = p - station.center;
  r -= r.dot(station.normal) * station.normal;
  if (r.norm() < 1e-9) return false;
  *e = r.normalized();
  const Eigen::Vector3d t2 = station.normal.cross(t1);
  *angle = std::atan2(e->dot(t2), e->dot(t1));
  return true;
}

double OutlineAt(const std::array<double, SectionShift::kDirections>& outline, double angle) {
  constexpr int n = SectionShift::kDirections;
  double x = angle / (2.0 * kPi) * n;
  x -= n * std::floor(x / n);
  const int i = static_cast<int>(std::floor(x)) % n;
  const double t = x - std::floor(x);
  return (1.0 - t) * outline[i] + t * outline[(i + 1) % n];
}

// Support function of the points `in` in 72 directions of the station plane, minus the centre's: h(e_k) - c . e_k.
std::array<double, SectionShift::kDirections> Support(const std::vector<Eigen::Vector3d>& in,
                                                      const AxisStation& station, const Eigen::Vector3d& t1,
                                                      const Eigen::Vector3d& centre) {
  std::array<double, SectionShift::kDirections> h;
  const Eigen::Vector3d t2 = station.normal.cross(t1);
  for (int k = 0; k < SectionShift::kDirections; ++k) {
    const double a = 2.0 * kPi * k / SectionShift::kDirections;
    const Eigen::Vector3d e = std::cos(a) * t1 + std::sin(a) * t2;
    double hi = -std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : in) hi = std::max(hi, (p - centre).dot(e));
    h[k] = hi;
  }
  return h;
}

// True when the points `in` surround `centre` in the station plane: each of 36 sectors of 10 degrees holds one. A
// section cut by the shortened top end (or by the top band left out of the scan) is a partial ring: its support
// function in the missing directions comes from the far side and reads as a move of the outline by up to the radius.
bool Surrounds(const std::vector<Eigen::Vector3d>& in, const AxisStation& station, const Eigen::Vector3d& t1,
               const Eigen::Vector3d& centre) {
  constexpr int kSectors = 36;
  std::array<bool, kSectors> seen{};
  const Eigen::Vector3d t2 = station.normal.cross(t1);
  for (const Eigen::Vector3d& p : in) {
    const Eigen::Vector3d r = p - centre;
    const double a = std::atan2(r.dot(t2), r.dot(t1));
    const int k = std::clamp(static_cast<int>(std::floor((a + kPi) / (2.0 * kPi) * kSectors)), 0, kSectors - 1);
    seen[k] = true;
  }
  return std::all_of(seen.begin(), seen.end(), [](bool b) { return b; });
}

std::vector<Eigen::Vector3d> InSlab(const std::vector<Eigen::Vector3d>& cloud, const AxisStation& s, double slab,
                                    double reach) {
  std::vector<Eigen::Vector3d> in;
  for (const Eigen::Vector3d& p : cloud) {
    const Eigen::Vector3d r = p - s.center;
    if (std::abs(r.dot(s.normal)) <= 0.5 * slab && r.norm() <= reach) in.push_back(p);
  }
  return in;
}

}  // namespace

SectionShift::Bracket SectionShift::Enclosing(const Eigen::Vector3d& p) const {
  Bracket b;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < stations.size(); ++i) {
    const double d = (p - stations[i].center).squaredNorm();
    if (d < best) {
      best = d;
      b.k = i;
    }
  }
  const double a = (p - stations[b.k].center).dot(stations[b.k].normal);
  b.j = a >= 0.0 ? std::min(b.k + 1, stations.size() - 1) : (b.k > 0 ? b.k - 1 : 0);
  if (b.j == b.k) return b;
  const double c = (p - stations[b.j].center).dot(stations[b.j].normal);
  b.t = std::abs(a) + std::abs(c) > 1e-12 ? std::abs(a) / (std::abs(a) + std::abs(c)) : 0.0;
  return b;
}

Eigen::Vector3d SectionShift::Axis(const Eigen::Vector3d& p) const {
  if (stations.empty()) return Eigen::Vector3d::Zero();
  return Axis(Enclosing(p));
}

Eigen::Vector3d SectionShift::Axis(const Bracket& b) const { return (1.0 - b.t) * shift[b.k] + b.t * shift[b.j]; }

Eigen::Vector3d SectionShift::Outline(const Eigen::Vector3d& p) const {
  if (stations.empty()) return Eigen::Vector3d::Zero();
  return Outline(p, Enclosing(p));
}

Eigen::Vector3d SectionShift::Outline(const Eigen::Vector3d& p, const Bracket& b) const {
  Eigen::Vector3d e;
  double angle = 0.0;
  if (!PlaneDirection(stations[b.k], t1[b.k], p, &e, &angle)) return Eigen::Vector3d::Zero();
  const double d = (1.0 - b.t) * OutlineAt(outline[b.k], angle) + b.t * OutlineAt(outline[b.j], angle);
  return d * e;
}

namespace {

// The in-plane axes carried along the axis (parallel transport), so that angle k means the same side of the part at
// every station, also through a bend where unitOrthogonal() would switch branches.
void TransportAxes(SectionShift* a) {
  for (std::size_t i = 0; i < a->stations.size(); ++i) {
    const Eigen::Vector3d& n = a->stations[i].normal;
    Eigen::Vector3d t = i == 0 ? n.unitOrthogonal() : a->t1[i - 1];
    t -= t.dot(n) * n;
    a->t1.push_back(t.norm() > 1e-6 ? Eigen::Vector3d(t.normalized()) : n.unitOrthogonal());
  }
}

// Measures station i's section of the scan against the reference's (slabs `slab` mm thick): its axis shift and
// outline move, and marks it measured; a section that is not complete in both is left unmeasured.
void MeasureStation(const std::vector<Eigen::Vector3d>& reference, const std::vector<Eigen::Vector3d>& scan,
                    double slab, std::size_t i, SectionShift* a) {
  const AxisStation& s = a->stations[i];
  const double reach = 1.5 * s.radius_mm + 2.0 * slab + 5.0;
  const SectionMeasure t = MeasureSection(reference, s, slab, reach);
  const SectionMeasure m = MeasureSection(scan, s, slab, reach);
  // A complete section only: a slab past the shortened, tilted top cuts a partial ring whose centre is not the axis.
  if (m.points == 0 || t.points == 0 || m.d_min_mm < 0.7 * t.d_min_mm || m.d_max_mm < 0.7 * t.d_max_mm ||
      m.d_max_mm > 1.25 * t.d_max_mm) {
    return;
  }
  const std::vector<Eigen::Vector3d> scan_in = InSlab(scan, s, slab, reach);
  const std::vector<Eigen::Vector3d> reference_in = InSlab(reference, s, slab, reach);
  if (!Surrounds(scan_in, s, a->t1[i], m.centroid) || !Surrounds(reference_in, s, a->t1[i], t.centroid)) return;
  const Eigen::Vector3d d = m.centroid - t.centroid;
  a->shift[i] = d - d.dot(s.normal) * s.normal;
  const std::array<double, SectionShift::kDirections> hs = Support(scan_in, s, a->t1[i], m.centroid);
  const std::array<double, SectionShift::kDirections> hr = Support(reference_in, s, a->t1[i], t.centroid);
  for (int k = 0; k < SectionShift::kDirections; ++k) a->outline[i][k] = hs[k] - hr[k];
  a->measured[i] = 1;
}

// Top: the last outline, and a straight line through the last measured axis offsets `ok` (up to 5 stations) in the
// arc length s, projected into each plane; the line is trusted over the shortened top end only (at most
// kExtrapolateMm of axis), then held.
void ExtrapolateTop(const std::vector<std::size_t>& ok, SectionShift* a) {
  const std::size_t n_fit = std::min<std::size_t>(ok.size(), 5);
  Eigen::Vector3d slope = Eigen::Vector3d::Zero(), mean = Eigen::Vector3d::Zero();
  double s_mean = 0.0;
  for (std::size_t k = ok.size() - n_fit; k < ok.size(); ++k) {
    mean += a->shift[ok[k]];
    s_mean += a->stations[ok[k]].s_mm;
  }
  mean /= static_cast<double>(n_fit);
  s_mean /= static_cast<double>(n_fit);
  double ss = 0.0;
  for (std::size_t k = ok.size() - n_fit; k < ok.size(); ++k) {
    const double ds = a->stations[ok[k]].s_mm - s_mean;
    slope += ds * (a->shift[ok[k]] - mean);
    ss += ds * ds;
  }
  if (ss > 0.0) slope /= ss;
  constexpr double kExtrapolateMm = 20.0;
  const double s_last = a->stations[ok.back()].s_mm;
  for (std::size_t i = ok.back() + 1; i < a->stations.size(); ++i) {
    const double s_i = std::min(a->stations[i].s_mm, s_last + kExtrapolateMm);
    const Eigen::Vector3d d = mean + slope * (s_i - s_mean);
    a->shift[i] = d - d.dot(a->stations[i].normal) * a->stations[i].normal;
    a->outline[i] = a->outline[ok.back()];
  }
}

// Gaps between the measured stations `ok`: linear between the measured neighbours.
void InterpolateGaps(const std::vector<std::size_t>& ok, SectionShift* a) {
  for (std::size_t k = 1; k < ok.size(); ++k) {
    for (std::size_t i = ok[k - 1] + 1; i < ok[k]; ++i) {
      const double t = static_cast<double>(i - ok[k - 1]) / static_cast<double>(ok[k] - ok[k - 1]);
      a->shift[i] = (1.0 - t) * a->shift[ok[k - 1]] + t * a->shift[ok[k]];
      for (int d = 0; d < SectionShift::kDirections; ++d) {
        a->outline[i][d] = (1.0 - t) * a->outline[ok[k - 1]][d] + t * a->outline[ok[k]][d];
      }
    }
  }
}

}  // namespace

SectionShift MeasureSectionShift(const std::vector<Eigen::Vector3d>& reference,
                                 const std::vector<Eigen::Vector3d>& scan, double step_mm) {
  SectionShift a;
  const double slab = 0.5 * step_mm;
  a.stations = CentralAxis(reference, step_mm, slab);
  TransportAxes(&a);
  a.shift.assign(a.stations.size(), Eigen::Vector3d::Zero());
  a.outline.assign(a.stations.size(), std::array<double, SectionShift::kDirections>{});
  a.measured.assign(a.stations.size(), 0);
  // Each station's section is measured on its own (its own slots), in parallel; the largest shift is taken after.
  ParallelFor(a.stations.size(), [&](std::size_t i) { MeasureStation(reference, scan, slab, i, &a); });
  std::vector<std::size_t> ok;
  for (std::size_t i = 0; i < a.stations.size(); ++i) {
    if (!a.measured[i]) continue;
    ok.push_back(i);
    a.max_measured_mm = std::max(a.max_measured_mm, a.shift[i].norm());
  }
  if (ok.empty()) return a;
  // Bottom: hold the first measured values.
  for (std::size_t i = 0; i < ok.front(); ++i) {
    a.shift[i] = a.shift[ok.front()];
    a.outline[i] = a.outline[ok.front()];
  }
  ExtrapolateTop(ok, &a);
  InterpolateGaps(ok, &a);
  return a;
}

std::vector<std::vector<Eigen::Vector3d>> EstimateCorrections(const planner::Plan& nominal, const ScanDeviation& scan,
                                                              const std::vector<Eigen::Vector3d>& scan_points,
                                                              const MeshDistance& reference_distance,
                                                              const std::vector<Eigen::Vector3d>& reference_points,
                                                              double bead_width_mm, double axis_step_mm,
                                                              CorrectionMethod method, int debug_level) {
  if (method == CorrectionMethod::kPoints) return LocalCorrections(nominal, scan, bead_width_mm);
  const SectionShift sections = MeasureSectionShift(reference_points, scan_points, axis_step_mm);
  // The scan moved back by the axis offset and the outline move of its section, measured again against the reference.
  std::vector<Eigen::Vector3d> recentred(scan.points.size());
  ParallelFor(scan.points.size(), [&](std::size_t j) {
    const Eigen::Vector3d p = scan.points[j] - sections.Axis(scan.points[j]);
    recentred[j] = p - sections.Outline(p);
  });
  const ScanDeviation local_scan = MeasureScanDeviation(recentred, reference_distance);
  std::vector<std::vector<Eigen::Vector3d>> s = LocalCorrections(nominal, local_scan, bead_width_mm);
  const int debug = debug_level;
  const bool print = debug >= 1, every_layer = debug >= 2;
  if (print) {
    std::fprintf(stderr, "sections: %zu stations, %zu measured, max measured axis shift %.3f mm, recentred max |d| %.3f\n",
                 sections.stations.size(),
                 static_cast<std::size_t>(std::count(sections.measured.begin(), sections.measured.end(), 1)),
                 sections.max_measured_mm, local_scan.max_abs_mm);
  }
  for (std::size_t l = 0; l < nominal.layers.size(); ++l) {
    const Eigen::Vector3d n = nominal.layers[l].build_dir_P.normalized();
    double axis_max = 0.0, outline_max = 0.0, local_max = 0.0;
    for (std::size_t i = 0; i < nominal.layers[l].points.size(); ++i) {
      const Eigen::Vector3d& p = nominal.layers[l].points[i].p_P;
      // The remainder is measured on the scan around p, which is only whole where the section is: at the stations
      // filled in from the measured ones (the shortened top end) the scan there is the rounded rim and the band left
      // out, and its closest-point deviations are not the wall's (part I: 1.6-3.9 mm of remainder on layers 164-168,
      // 0.1-0.6 mm below). There only the section terms act (docs/compensation.md gives what it changed).
      Eigen::Vector3d axis = Eigen::Vector3d::Zero(), outline = Eigen::Vector3d::Zero();
      if (!sections.stations.empty()) {
        const SectionShift::Bracket b = sections.Enclosing(p);
        if (!sections.measured[b.k]) s[l][i].setZero();
        axis = sections.Axis(b);
        outline = sections.Outline(p, b);
      }
      const Eigen::Vector3d a = axis + outline;
      if (print) {
        axis_max = std::max(axis_max, (axis - axis.dot(n) * n).norm());
        outline_max = std::max(outline_max, (outline - outline.dot(n) * n).norm());
        local_max = std::max(local_max, s[l][i].norm());
      }
      s[l][i] += a - a.dot(n) * n;
    }
    if (print && (every_layer || l % 10 == 0 || l + 1 == nominal.layers.size())) {
      std::fprintf(stderr, "layer %3zu  max|axis| %6.3f  max|outline| %6.3f  max|local| %6.3f\n", l, axis_max,
                   outline_max, local_max);
    }
  }
  return s;
}

double CorrectionError(const planner::Plan& nominal, const planner::Plan& current, const DistortionField& field,
                       const std::vector<std::vector<Eigen::Vector3d>>& s, int debug_level) {
  const int debug = debug_level;
  const bool print = debug >= 1, every_layer = debug >= 2;
  double worst = 0.0;
  for (std::size_t l = 0; l < nominal.layers.size(); ++l) {
    const Eigen::Vector3d n = nominal.layers[l].build_dir_P.normalized();
    double layer_worst = 0.0, s_max = 0.0, e_max = 0.0, axial = 0.0;
    for (std::size_t i = 0; i < nominal.layers[l].points.size(); ++i) {
      // Welded points on the part only: travel points and points off the deposit have no displacement.
      if (!current.layers[l].points[i].weld) continue;
      const Eigen::Vector3d r = current.layers[l].points[i].p_P;
      const Eigen::Vector3d u = field.Displacement(r);
      if (u.squaredNorm() == 0.0) continue;
      Eigen::Vector3d e = r + u - nominal.layers[l].points[i].p_P;
      axial = std::max(axial, std::abs(e.dot(n)));
      e -= e.dot(n) * n;
      layer_worst = std::max(layer_worst, (s[l][i] - e).norm());
      s_max = std::max(s_max, s[l][i].norm());
      e_max = std::max(e_max, e.norm());
    }
    worst = std::max(worst, layer_worst);
    if (print && (every_layer || l % 10 == 0 || l + 1 == nominal.layers.size())) {
      std::fprintf(stderr, "layer %3zu  max|S| %6.3f  max|e_true| %6.3f  max|S-e| %6.3f  max|axial| %6.3f\n", l, s_max,
                   e_max, layer_worst, axial);
    }
  }
  return worst;
}

}  // namespace waam::twin::internal
