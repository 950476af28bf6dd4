// Vertex removal on flat regions and straight creases, with exact integer geometry.
#include "twin/scanner/flat_vertices.h"

#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <algorithm>
#include <utility>

namespace waam::twin {
namespace {

using P3 = Eigen::Matrix<std::int64_t, 3, 1>;
using Facet = std::array<int, 3>;

std::uint64_t EdgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32 | static_cast<std::uint32_t>(b);
}

// The facet's normal divided by the gcd of its components: equal for facets of one orientation.
P3 ReducedNormal(const P3& a, const P3& b, const P3& c) {
  P3 n = (b - a).cross(c - a);
  const std::int64_t g = std::gcd(std::gcd(std::abs(n.x()), std::abs(n.y())), std::abs(n.z()));
  return g > 0 ? P3(n / g) : n;
}

// 128-bit products of 64-bit coordinates (a GCC/Clang extension, marked so that -Wpedantic accepts it).
__extension__ using Int128 = __int128;

// Twice the area of triangle a, b, c projected on n: > 0 when counter-clockwise seen from the side n points to.
Int128 Side(const P3& a, const P3& b, const P3& c, const P3& n) {
  const P3 k = (b - a).cross(c - a);
  return static_cast<Int128>(k.x()) * n.x() + static_cast<Int128>(k.y()) * n.y() +
         static_cast<Int128>(k.z()) * n.z();
}

// Ear clipping of the planar polygon `ring` (vertex ids, counter-clockwise about n): an ear is a strict convex
// vertex whose triangle holds no other vertex of the polygon, not even on its edges (so no vertex is left on a
// diagonal: no T-junction, no degenerate facet). Appends ring.size() - 2 triangles; false when it finds no ear.
bool ClipEars(std::vector<int> ring, const std::vector<P3>& p, const P3& n, std::vector<Facet>* out) {
  while (ring.size() >= 3) {
    const std::size_t m = ring.size();
    bool clipped = false;
    for (std::size_t i = 0; i < m && !clipped; ++i) {
      const int a = ring[(i + m - 1) % m], b = ring[i], c = ring[(i + 1) % m];
      if (Side(p[a], p[b], p[c], n) <= 0) continue;
      bool empty = true;
      for (std::size_t j = 0; j < m && empty && m > 3; ++j) {
        const int q = ring[j];
        if (q == a || q == b || q == c) continue;
        empty = !(Side(p[a], p[b], p[q], n) >= 0 && Side(p[b], p[c], p[q], n) >= 0 && Side(p[c], p[a], p[q], n) >= 0);
      }
      if (!empty) continue;
      out->push_back({a, b, c});
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped) return false;
    if (m == 3) return true;
  }
  return false;
}

// The mesh being thinned: facets (dead ones flagged) and the live facets at each vertex.
struct Mesh {
  std::vector<P3> p;
  std::vector<Facet>* facets;
  std::vector<char> dead;
  std::vector<std::vector<int>> at;  // live facets at each vertex
};

// The hole vertex v leaves, triangulated in its plane(s): the fan's link as one polygon when its facets are
// coplanar, two polygons split at the crease neighbours when they lie in two planes meeting along a straight line
// through v. Empty when v must stay.
std::vector<Facet> Refill(const Mesh& m, int v) {
  const std::vector<Facet>& f = *m.facets;
  // The link: facet (v, a, b) goes a -> b (counter-clockwise round v seen from outside).
  std::vector<std::array<int, 3>> link;  // (a, b, facet)
  for (int i : m.at[v]) {
    const Facet& t = f[static_cast<std::size_t>(i)];
    const int k = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    const int a = t[(k + 1) % 3];
    for (const auto& l : link) {
      if (l[0] == a) return {};  // not one fan
    }
    link.push_back({a, t[(k + 2) % 3], i});
  }
  std::vector<int> ring, ring_facet;
  for (std::size_t at = 0;;) {
    ring.push_back(link[at][0]);
    ring_facet.push_back(link[at][2]);
    const int b = link[at][1];
    if (b == ring.front()) break;
    if (ring.size() == link.size()) return {};
    at = 0;
    while (at < link.size() && link[at][0] != b) ++at;
    if (at == link.size()) return {};
  }
  if (ring.size() != link.size()) return {};  // two fans meet at v
  const std::size_t n = ring.size();
  std::vector<P3> normal(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Facet& t = f[static_cast<std::size_t>(ring_facet[k])];
    normal[k] = ReducedNormal(m.p[t[0]], m.p[t[1]], m.p[t[2]]);
  }
  std::vector<std::size_t> turns;  // positions k where facet k leaves the plane of facet k - 1
  for (std::size_t k = 0; k < n; ++k) {
    if (normal[k] != normal[(k + n - 1) % n]) turns.push_back(k);
  }
  std::vector<Facet> fill;
  if (turns.empty()) return ClipEars(ring, m.p, normal[0], &fill) ? fill : std::vector<Facet>{};
  if (turns.size() != 2) return {};
  const P3 d1 = m.p[ring[turns[0]]] - m.p[v], d2 = m.p[ring[turns[1]]] - m.p[v];
  if (!d1.cross(d2).isZero() || d1.dot(d2) >= 0) return {};  // a corner, not a straight crease
  for (int side = 0; side < 2; ++side) {
    const std::size_t from = turns[side], to = turns[1 - side];
    std::vector<int> half;
    for (std::size_t k = from;; k = (k + 1) % n) {
      half.push_back(ring[k]);
      if (k == to) break;
    }
    if (!ClipEars(half, m.p, normal[from], &fill)) return {};
  }
  return fill;
}

// True when vertices a and b share a live facet (an edge of the mesh).
bool Adjacent(const Mesh& m, int a, int b) {
  for (int i : m.at[static_cast<std::size_t>(a)]) {
    const Facet& t = (*m.facets)[static_cast<std::size_t>(i)];
    if (t[0] == b || t[1] == b || t[2] == b) return true;
  }
  return false;
}

// True when `fill` replaces a fan without repeating an edge: every edge it adds is new to the mesh and used twice
// within it (the link's edges are kept, once each).
bool FitsMesh(const Mesh& m, const std::vector<Facet>& fill) {
  std::vector<std::pair<std::uint64_t, int>> uses;  // edge, facets of `fill` using it
  for (const Facet& t : fill) {
    for (int c = 0; c < 3; ++c) {
      const std::uint64_t e = EdgeKey(t[c], t[(c + 1) % 3]);
      auto it = std::find_if(uses.begin(), uses.end(), [&](const auto& u) { return u.first == e; });
      if (it == uses.end()) {
        uses.emplace_back(e, 1);
      } else {
        ++it->second;
      }
    }
  }
  for (const auto& [edge, count] : uses) {
    const int a = static_cast<int>(edge >> 32), b = static_cast<int>(edge & 0xffffffffu);
    // An edge of the link is an edge of the mesh not through v; any other must be new.
    if (Adjacent(m, a, b) ? count != 1 : count != 2) return false;
  }
  return true;
}

// Replaces v's fan by `fill`.
void Replace(Mesh* m, int v, const std::vector<Facet>& fill) {
  std::vector<Facet>& f = *m->facets;
  for (int i : m->at[v]) {
    m->dead[static_cast<std::size_t>(i)] = 1;
  }
  for (int i : m->at[v]) {
    for (int c : f[static_cast<std::size_t>(i)]) {
      if (c == v) continue;
      auto& list = m->at[static_cast<std::size_t>(c)];
      std::erase_if(list, [&](int j) { return m->dead[static_cast<std::size_t>(j)] != 0; });
    }
  }
  m->at[static_cast<std::size_t>(v)].clear();
  for (const Facet& t : fill) {
    const int id = static_cast<int>(f.size());
    f.push_back(t);
    m->dead.push_back(0);
    for (int c : t) m->at[static_cast<std::size_t>(c)].push_back(id);
  }
}

}  // namespace

std::size_t RemoveFlatVertices(const std::vector<Eigen::Vector3i>& points, std::vector<Facet>* facets) {
  Mesh m;
  m.facets = facets;
  m.p.reserve(points.size());
  for (const Eigen::Vector3i& q : points) m.p.push_back(q.cast<std::int64_t>());
  m.dead.assign(facets->size(), 0);
  m.at.resize(points.size());
  for (std::size_t i = 0; i < facets->size(); ++i) {
    for (int c : (*facets)[i]) m.at[static_cast<std::size_t>(c)].push_back(static_cast<int>(i));
  }
  std::size_t removed = 0;
  for (int v = 0; v < static_cast<int>(points.size()); ++v) {
    if (m.at[static_cast<std::size_t>(v)].size() < 3) continue;
    const std::vector<Facet> fill = Refill(m, v);
    if (fill.empty() || !FitsMesh(m, fill)) continue;
    Replace(&m, v, fill);
    ++removed;
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < facets->size(); ++i) {
    if (m.dead[i] == 0) (*facets)[kept++] = (*facets)[i];
  }
  facets->resize(kept);
  return removed;
}

}  // namespace waam::twin
