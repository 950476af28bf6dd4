// Planar slicer: a sweep over facets sorted by their lowest z with an active set, cut points identified by the mesh
// edge they lie on, segments chained through shared edge ids, and loops nested by depth (Ding et al. 2014, 3.1 step 1).
#include "planner/slicing/planar_slicer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

#include "models/core/error.h"

namespace waam::planner {
namespace {

std::uint64_t EdgeKey(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

// One facet/plane intersection: from the cut on edge `from` to the cut on edge `to`.
struct Segment {
  std::uint64_t from;
  std::uint64_t to;
  Eigen::Vector2d p_from;
  Eigen::Vector2d p_to;
};

// The cut of the mesh edge u-v (u below, v at or above h); computed from the lower vertex so that both facets
// sharing the edge get the same point bit for bit.
Eigen::Vector2d CutPoint(const Eigen::Vector3d& below, const Eigen::Vector3d& above, double h) {
  // A vertex on the plane is its own cut (interpolating with t = 1 would not give it back bit for bit).
  if (above.z() == h) return above.head<2>();
  const double t = (h - below.z()) / (above.z() - below.z());
  return below.head<2>() + t * (above.head<2>() - below.head<2>());
}

// Chains the segments of one height into closed rings; counts the chains that do not close.
std::vector<Ring> ChainSegments(const std::vector<Segment>& segments, std::size_t* open_chains) {
  // Each cut edge is shared by two facets, so by two segments; chaining ignores segment direction, which makes it
  // indifferent to inconsistent facet orientation (rings are oriented by nesting afterwards).
  std::unordered_map<std::uint64_t, std::array<int, 2>> by_edge;
  by_edge.reserve(segments.size() * 2);
  for (int s = 0; s < static_cast<int>(segments.size()); ++s) {
    for (std::uint64_t key : {segments[s].from, segments[s].to}) {
      auto [it, inserted] = by_edge.try_emplace(key, std::array<int, 2>{s, -1});
      if (!inserted && it->second[1] < 0) it->second[1] = s;  // a third use (non-manifold) is ignored
    }
  }
  auto other_segment = [&](std::uint64_t key, int s) {
    const std::array<int, 2>& pair = by_edge.at(key);
    return pair[0] == s ? pair[1] : pair[0];
  };
  std::vector<char> used(segments.size(), 0);
  std::vector<Ring> rings;
  for (int start = 0; start < static_cast<int>(segments.size()); ++start) {
    if (used[start]) continue;
    used[start] = 1;
    Ring ring = {segments[start].p_from};
    std::uint64_t key = segments[start].to;
    Eigen::Vector2d point = segments[start].p_to;
    int s = start;
    bool closed = false;
    while (true) {
      if (key == segments[start].from) {
        closed = true;
        break;
      }
      ring.push_back(point);
      const int next = other_segment(key, s);
      if (next < 0 || used[next]) break;
      used[next] = 1;
      const bool forward = segments[next].from == key;
      key = forward ? segments[next].to : segments[next].from;
      point = forward ? segments[next].p_to : segments[next].p_from;
      s = next;
    }
    if (closed) {
      rings.push_back(std::move(ring));
      continue;
    }
    // Open: consume the rest of the chain backwards from the start so it is counted once.
    ++*open_chains;
    key = segments[start].from;
    s = start;
    for (int prev = other_segment(key, s); prev >= 0 && !used[prev]; prev = other_segment(key, s)) {
      used[prev] = 1;
      key = segments[prev].from == key ? segments[prev].to : segments[prev].from;
      s = prev;
    }
  }
  return rings;
}

}  // namespace

std::vector<PolygonWithHoles> NestRings(std::vector<Ring> rings) {
  struct Loop {
    Ring ring;
    double area;
    Eigen::Vector2d lo, hi;
  };
  std::vector<Loop> loops;
  for (Ring& ring : rings) {
    // Cuts through a vertex lying on the plane repeat that point; drop the repeats.
    Ring clean;
    for (const Eigen::Vector2d& p : ring) {
      if (clean.empty() || p != clean.back()) clean.push_back(p);
    }
    while (clean.size() > 1 && clean.front() == clean.back()) clean.pop_back();
    const double area = SignedArea(clean);
    if (clean.size() < 3 || area == 0.0) continue;
    Loop loop{std::move(clean), std::abs(area), {}, {}};
    loop.lo = loop.hi = loop.ring.front();
    for (const Eigen::Vector2d& p : loop.ring) {
      loop.lo = loop.lo.cwiseMin(p);
      loop.hi = loop.hi.cwiseMax(p);
    }
    if (area < 0) std::reverse(loop.ring.begin(), loop.ring.end());  // all CCW for now
    loops.push_back(std::move(loop));
  }
  // A ring can only lie inside a larger one: sort by decreasing area, then its depth is the number of earlier rings
  // containing it and its parent the last (smallest) of them.
  std::stable_sort(loops.begin(), loops.end(), [](const Loop& a, const Loop& b) { return a.area > b.area; });
  const std::size_t n = loops.size();
  std::vector<int> depth(n, 0), parent(n, -1), region_of(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const Loop& outer = loops[j];
      if ((loops[i].lo.array() < outer.lo.array()).any() || (loops[i].hi.array() > outer.hi.array()).any()) continue;
      if (PointInRing(loops[i].ring.front(), outer.ring)) {
        ++depth[i];
        parent[i] = static_cast<int>(j);
      }
    }
  }
  std::vector<PolygonWithHoles> regions;
  for (std::size_t i = 0; i < n; ++i) {
    if (depth[i] % 2 == 0) {
      region_of[i] = static_cast<int>(regions.size());
      regions.push_back({std::move(loops[i].ring), {}});
    } else {
      Ring hole = std::move(loops[i].ring);
      std::reverse(hole.begin(), hole.end());
      regions[region_of[parent[i]]].holes.push_back(std::move(hole));
    }
  }
  return regions;
}

std::vector<std::vector<PolygonWithHoles>> SlicePlanar(const TriangleMesh& mesh, const std::vector<double>& heights_mm,
                                                       SliceReport* report) {
  for (std::size_t i = 0; i < heights_mm.size(); ++i) {
    WAAM_THROW_UNLESS(std::isfinite(heights_mm[i]),
                      "slice height " << i << " = " << heights_mm[i] << " mm: must be a finite number");
  }
  const std::size_t facet_count = mesh.facets.size();
  std::vector<double> z_min(facet_count), z_max(facet_count);
  for (std::size_t f = 0; f < facet_count; ++f) {
    const std::array<int, 3>& t = mesh.facets[f];
    const double a = mesh.vertices[t[0]].z(), b = mesh.vertices[t[1]].z(), c = mesh.vertices[t[2]].z();
    z_min[f] = std::min({a, b, c});
    z_max[f] = std::max({a, b, c});
  }
  std::vector<int> by_min(facet_count);
  std::iota(by_min.begin(), by_min.end(), 0);
  std::stable_sort(by_min.begin(), by_min.end(), [&](int a, int b) { return z_min[a] < z_min[b]; });
  std::vector<std::size_t> order(heights_mm.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return heights_mm[a] < heights_mm[b]; });

  SliceReport local;
  SliceReport& stats = report ? *report : local;
  stats = SliceReport{};
  std::vector<std::vector<PolygonWithHoles>> slices(heights_mm.size());
  std::vector<int> active;
  std::vector<Segment> segments;
  std::size_t next_facet = 0;
  for (std::size_t index : order) {
    const double h = heights_mm[index];
    // Symbolic perturbation: a vertex at z == h is above, so a facet is cut iff z_min < h <= z_max.
    while (next_facet < facet_count && z_min[by_min[next_facet]] < h) active.push_back(by_min[next_facet++]);
    active.erase(std::remove_if(active.begin(), active.end(), [&](int f) { return z_max[f] < h; }), active.end());
    stats.facet_tests += active.size();

    segments.clear();
    for (int f : active) {
      const std::array<int, 3>& t = mesh.facets[f];
      Segment segment{0, 0, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
      int found = 0;
      for (int k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3];
        const bool a_above = mesh.vertices[a].z() >= h;
        const bool b_above = mesh.vertices[b].z() >= h;
        if (a_above == b_above) continue;
        // Walking the facet counter-clockwise, the cut leaves on the edge going up and enters on the edge going
        // down; from -> to then runs with the material on the left for an outward-oriented facet.
        const Eigen::Vector2d p = a_above ? CutPoint(mesh.vertices[b], mesh.vertices[a], h)
                                          : CutPoint(mesh.vertices[a], mesh.vertices[b], h);
        if (a_above) {
          segment.from = EdgeKey(a, b);
          segment.p_from = p;
        } else {
          segment.to = EdgeKey(a, b);
          segment.p_to = p;
        }
        ++found;
      }
      if (found == 2) segments.push_back(segment);
    }
    stats.segments += segments.size();
    std::size_t open = 0;
    slices[index] = NestRings(ChainSegments(segments, &open));
    if (open > 0) {
      WAAM_THROW_UNLESS(report != nullptr, "slice at z = " << h << " mm: " << open
                                                           << " contour chains do not close; the mesh is not "
                                                           << "watertight (check it with `waam inspect`)");
      stats.open_chains += open;
      stats.open_chain_heights_mm.insert(stats.open_chain_heights_mm.end(), open, h);
    }
  }
  return slices;
}

}  // namespace waam::planner
