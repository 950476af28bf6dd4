// The order of a layer's islands (or passes): path.island_order.
#include "planner/timeline/island_order.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "planner/geometry/polygon.h"

namespace waam::planner {
namespace {

// One pass of a layer: points [begin, end), an arc-off point then weld points.
struct PassRange {
  std::size_t begin = 0;
  std::size_t end = 0;
};

// A unit of a layer: an island's passes (in planned order) and where its metal lies.
struct Unit {
  std::vector<PassRange> passes;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // of its weld points, mm
  Eigen::Vector3d lo, hi;                              // bounding box of its weld points grown by two bead widths, mm
  double last_end_s = -std::numeric_limits<double>::infinity();  // its island's last deposition end (proxy clock), s
};

// An island followed from layer to layer.
struct Island {
  Eigen::Vector3d centroid;
  double last_end_s = 0.0;
};

// The passes of a layer, or nothing when the layer continues a pass from the layer before (a spiral).
std::vector<PassRange> SplitPasses(const LayerPath& layer) {
  std::vector<PassRange> passes;
  const std::vector<PathPoint>& pts = layer.points;
  if (!pts.empty() && pts.front().weld) return passes;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    if (pts[i].weld || !pts[i + 1].weld) continue;
    std::size_t end = i + 1;
    while (end < pts.size() && pts[end].weld) ++end;
    passes.push_back({i, end});
    i = end - 1;
  }
  return passes;
}

// The region of the layer's slice holding point p_P (index), or -1.
int RegionOf(const LayerPath& layer, const Eigen::Vector3d& p_P) {
  if (!layer.slice_in_plane) return -1;
  const Eigen::Vector2d p = layer.slice_axes_P.transpose() * (p_P - layer.slice_origin_P);
  for (std::size_t r = 0; r < layer.slice.size(); ++r) {
    const PolygonWithHoles& region = layer.slice[r];
    if (!PointInRing(p, region.outer)) continue;
    bool in_hole = false;
    for (const Ring& hole : region.holes) in_hole = in_hole || PointInRing(p, hole);
    if (!in_hole) return static_cast<int>(r);
  }
  return -1;
}

// The units of a layer: islands when several regions hold passes, else single passes.
std::vector<Unit> UnitsOf(const LayerPath& layer, const std::vector<PassRange>& passes) {
  std::vector<int> region(passes.size());
  std::vector<int> regions_used;
  for (std::size_t k = 0; k < passes.size(); ++k) {
    region[k] = RegionOf(layer, layer.points[passes[k].begin + 1].p_P);
    if (region[k] >= 0 && std::find(regions_used.begin(), regions_used.end(), region[k]) == regions_used.end()) {
      regions_used.push_back(region[k]);
    }
  }
  const bool by_region = regions_used.size() > 1;
  std::vector<Unit> units;
  std::vector<int> unit_of_region(layer.slice.size(), -1);
  for (std::size_t k = 0; k < passes.size(); ++k) {
    int u = -1;
    if (by_region && region[k] >= 0) u = unit_of_region[static_cast<std::size_t>(region[k])];
    if (u < 0) {
      u = static_cast<int>(units.size());
      units.emplace_back();
      if (by_region && region[k] >= 0) unit_of_region[static_cast<std::size_t>(region[k])] = u;
    }
    units[static_cast<std::size_t>(u)].passes.push_back(passes[k]);
  }
  for (Unit& unit : units) {
    std::size_t n = 0;
    double width = 0.0;
    unit.lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    unit.hi = -unit.lo;
    for (const PassRange& pass : unit.passes) {
      for (std::size_t i = pass.begin + 1; i < pass.end; ++i) {
        const PathPoint& p = layer.points[i];
        unit.centroid += p.p_P;
        unit.lo = unit.lo.cwiseMin(p.p_P);
        unit.hi = unit.hi.cwiseMax(p.p_P);
        width = std::max(width, p.bead_width_mm);
        ++n;
      }
    }
    unit.centroid /= static_cast<double>(n);
    unit.lo.array() -= 2.0 * width;
    unit.hi.array() += 2.0 * width;
  }
  return units;
}

// The proxy clock over one pass: travel from `*at` to its start at the rapid speed, then its arc time.
double PassTime(const LayerPath& layer, const PassRange& pass, const TimelineSettings& timing,
                const Eigen::Vector3d** at) {
  const std::vector<PathPoint>& pts = layer.points;
  double t = *at != nullptr ? (pts[pass.begin].p_P - **at).norm() / timing.rapid_speed_mm_s : 0.0;
  t += timing.arc_start_s + timing.arc_end_s;
  for (std::size_t i = pass.begin + 1; i < pass.end; ++i) {
    if (pts[i].speed_mm_s > 0.0) t += (pts[i].p_P - pts[i - 1].p_P).norm() / pts[i].speed_mm_s;
  }
  *at = &pts[pass.end - 1].p_P;
  return t;
}

// Matches each unit to the nearest earlier island inside its grown box (index into islands, or -1).
std::vector<int> MatchIslands(const std::vector<Unit>& units, const std::vector<Island>& islands) {
  std::vector<int> match(units.size(), -1);
  for (std::size_t u = 0; u < units.size(); ++u) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < islands.size(); ++i) {
      const Eigen::Vector3d& c = islands[i].centroid;
      const bool inside = (c.array() >= units[u].lo.array()).all() && (c.array() <= units[u].hi.array()).all();
      const double d = (c - units[u].centroid).norm();
      if (inside && d < best) best = d, match[u] = static_cast<int>(i);
    }
  }
  return match;
}

}  // namespace

IslandOrderReport OrderIslands(IslandOrder order, const TimelineSettings& timing, Plan* plan) {
  IslandOrderReport report;
  if (order == IslandOrder::kAsPlanned) return report;
  std::vector<Island> islands;
  double clock = 0.0;
  const Eigen::Vector3d* at = nullptr;  // where the torch is (the proxy clock's travel)
  for (std::size_t l = 0; l < plan->layers.size(); ++l) {
    LayerPath& layer = plan->layers[l];
    const std::vector<PassRange> passes = SplitPasses(layer);
    std::vector<Unit> units = UnitsOf(layer, passes);
    report.max_units = std::max(report.max_units, units.size());
    const std::vector<int> match = MatchIslands(units, islands);
    for (std::size_t u = 0; u < units.size(); ++u) {
      if (match[u] >= 0) units[u].last_end_s = islands[static_cast<std::size_t>(match[u])].last_end_s;
    }
    std::vector<std::size_t> sequence(units.size());
    std::iota(sequence.begin(), sequence.end(), 0);
    if (units.size() >= 2) {
      if (order == IslandOrder::kRoundRobin) {
        std::rotate(sequence.begin(), sequence.begin() + static_cast<std::ptrdiff_t>(l % units.size()),
                    sequence.end());
      } else {
        std::stable_sort(sequence.begin(), sequence.end(),
                         [&](std::size_t a, std::size_t b) { return units[a].last_end_s < units[b].last_end_s; });
      }
    }
    // The proxy clock over the layer in its new order; each unit's island remembers when it ended.
    for (std::size_t u : sequence) {
      for (const PassRange& pass : units[u].passes) clock += PassTime(layer, pass, timing, &at);
      if (match[u] >= 0) {
        islands[static_cast<std::size_t>(match[u])] = {units[u].centroid, clock};
      } else {
        islands.push_back({units[u].centroid, clock});
      }
    }
    if (std::is_sorted(sequence.begin(), sequence.end())) {
      if (!layer.points.empty()) at = &layer.points.back().p_P;
      continue;
    }
    // Rebuild the layer's points: the units' passes in the new order.
    std::vector<PathPoint> points;
    points.reserve(layer.points.size());
    for (std::size_t u : sequence) {
      for (const PassRange& pass : units[u].passes) {
        points.insert(points.end(), layer.points.begin() + static_cast<std::ptrdiff_t>(pass.begin),
                      layer.points.begin() + static_cast<std::ptrdiff_t>(pass.end));
      }
    }
    layer.points = std::move(points);
    at = &layer.points.back().p_P;
    ++report.layers_reordered;
  }
  return report;
}

}  // namespace waam::planner
