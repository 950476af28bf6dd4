// Greedy meshing of the exposed voxel faces, with T-junctions split so that the surface stays closed.
#include "twin/scanner/voxel_surface.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "models/core/error.h"
#include "models/core/progress.h"
#include "twin/scanner/flat_vertices.h"
#include "twin/scanner/point_hash.h"

namespace waam::twin {
namespace {

// Occupancy for the mesh: the grid's metal (z >= 0; the substrate is air here) plus the voxels filled for manifoldness.
class MeshOccupancy {
 public:
  explicit MeshOccupancy(const VoxelGrid& grid) : grid_(grid) {}
  bool operator()(const Eigen::Vector3i& v) const {
    return grid_.Occupied(v) || (!filled_.empty() && filled_.count(CellKey(v)) != 0);
  }
  bool Fill(const Eigen::Vector3i& v) { return filled_.insert(CellKey(v)).second; }

 private:
  const VoxelGrid& grid_;
  std::unordered_set<std::uint64_t> filled_;
};

const std::array<Eigen::Vector3i, 6> kDirs = {Eigen::Vector3i(1, 0, 0),  Eigen::Vector3i(-1, 0, 0),
                                              Eigen::Vector3i(0, 1, 0),  Eigen::Vector3i(0, -1, 0),
                                              Eigen::Vector3i(0, 0, 1),  Eigen::Vector3i(0, 0, -1)};

// Examines voxel v: if it has an exposed face it goes to `surface`; for every pair of voxels touching v along an edge
// only (both voxels between them empty), one of the two empty voxels is filled for the mesh and goes to `filled`.
// Returns the number of its exposed faces.
int Examine(const Eigen::Vector3i& v, MeshOccupancy* occ, std::vector<Eigen::Vector3i>* surface,
            std::vector<Eigen::Vector3i>* filled) {
  bool empty[6];
  int exposed = 0;
  for (int d = 0; d < 6; ++d) exposed += (empty[d] = !(*occ)(v + kDirs[d])) ? 1 : 0;
  if (exposed == 0) return 0;
  surface->push_back(v);
  for (int d1 = 0; d1 < 6; ++d1) {
    for (int d2 = d1 + 1; d2 < 6; ++d2) {
      if (d1 / 2 == d2 / 2 || !empty[d1] || !empty[d2] || !(*occ)(v + kDirs[d1] + kDirs[d2])) continue;
      // Fill above the substrate: of two directions on different axes at most one is -z.
      const int d = (v + kDirs[d1]).z() >= 0 ? d1 : d2;
      if (occ->Fill(v + kDirs[d])) filled->push_back(v + kDirs[d]);
      empty[d] = false;
    }
  }
  return exposed;
}

// The voxels with an exposed face, after filling every edge-only contact (filled voxels are examined in turn).
// Stops early, returning false, once more than `max_faces` exposed faces are seen.
bool SurfaceVoxels(const VoxelGrid& grid, MeshOccupancy* occ, std::size_t max_faces,
                   std::vector<Eigen::Vector3i>* surface) {
  std::vector<Eigen::Vector3i> filled;
  std::size_t faces = 0;
  grid.ForEach([&](const VoxelIndex& v, const VoxelData&) {
    if (faces <= max_faces) faces += static_cast<std::size_t>(Examine(v, occ, surface, &filled));
  });
  while (!filled.empty() && faces <= max_faces) {
    std::vector<Eigen::Vector3i> next;
    for (const Eigen::Vector3i& v : filled) faces += static_cast<std::size_t>(Examine(v, occ, surface, &next));
    filled = std::move(next);
  }
  return faces <= max_faces;
}

// One exposed face: direction d (0..5, axis d / 2, + when even), the plane's corner coordinate along the axis, and
// the voxel's coordinates along the next two axes (axis + 1, axis + 2 mod 3).
struct Face {
  int d, plane, v, u;
  bool operator<(const Face& o) const { return std::tie(d, plane, v, u) < std::tie(o.d, o.plane, o.v, o.u); }
  bool operator==(const Face& o) const { return std::tie(d, plane, v, u) == std::tie(o.d, o.plane, o.v, o.u); }
};

// A rectangle of faces: voxels u0..u1, v0..v1 (inclusive) of one plane.
struct Quad {
  int d, plane, u0, u1, v0, v1;
};

// Greedy rectangles of one plane's faces (sorted by v, u): from the first face not yet taken (a corner: nothing free
// before it in its row or in any row below) the run of free faces along u, grown along v for as many rows as hold
// all of it. Appends the rectangles to `quads`. (Which rectangles does not matter for the facets: their corners
// inside the plane's region are removed afterwards.)
void MergePlane(const Face* faces, std::size_t count, std::vector<Quad>* quads) {
  auto key = [](int u, int v) {
    return static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 32 | static_cast<std::uint32_t>(v);
  };
  std::unordered_set<std::uint64_t> free;  // faces not yet in a rectangle
  free.reserve(count);
  for (std::size_t i = 0; i < count; ++i) free.insert(key(faces[i].u, faces[i].v));
  for (std::size_t i = 0; i < count; ++i) {
    const Face& f = faces[i];
    if (free.count(key(f.u, f.v)) == 0) continue;
    int width = 0;
    while (free.count(key(f.u + width, f.v)) != 0) ++width;
    int v1 = f.v;
    for (bool full = true; full;) {
      for (int w = 0; w < width && full; ++w) full = free.count(key(f.u + w, v1 + 1)) != 0;
      if (full) ++v1;
    }
    for (int v = f.v; v <= v1; ++v) {
      for (int u = f.u; u < f.u + width; ++u) free.erase(key(u, v));
    }
    quads->push_back({f.d, f.plane, f.u, f.u + width - 1, f.v, v1});
  }
}

// The rectangles of every plane of `faces` (sorted by d, plane, v, u).
std::vector<Quad> MergeFaces(const std::vector<Face>& faces) {
  std::vector<Quad> quads;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i;
    while (j < faces.size() && faces[j].d == faces[i].d && faces[j].plane == faces[i].plane) ++j;
    MergePlane(&faces[i], j - i, &quads);
    i = j;
  }
  return quads;
}

// The 3D corner (in voxel-corner units) of plane point (u, v) of a quad with axis a.
Eigen::Vector3i Corner(int axis, int plane, int u, int v) {
  Eigen::Vector3i p;
  p[axis] = plane;
  p[(axis + 1) % 3] = u;
  p[(axis + 2) % 3] = v;
  return p;
}

// The quad corners sorted for the lines along one axis: by the two other coordinates, then the one along the axis,
// so the corners on a line segment are one contiguous range.
struct LineIndex {
  int axis;
  std::vector<Eigen::Vector3i> corners;
  std::array<int, 3> Key(const Eigen::Vector3i& p) const {
    return {p[(axis + 1) % 3], p[(axis + 2) % 3], p[axis]};
  }
  bool Less(const Eigen::Vector3i& a, const Eigen::Vector3i& b) const { return Key(a) < Key(b); }
};

// Triangulates a rectangle whose boundary `ring` (vertex ids, counter-clockwise) carries the corners of the
// rectangles touching it; `points` are the ring's positions. Ear clipping on a convex polygon with collinear vertices:
// a vertex is clipped only where it is a strict corner (off the line of its two neighbours) and the polygon left still
// has three strict corners (else it would collapse onto a line). A polygon of n vertices becomes n - 2 triangles,
// none degenerate, and every ring vertex stays on the boundary, so the neighbours' edges meet it (no T-junction
// cracks). Such an ear always exists: with four strict corners or more any of them will do; with three, the one next
// to a side carrying a point turns that point into a strict corner.
void Triangulate(std::vector<int> ring, std::vector<Eigen::Vector3i> points, std::vector<std::array<int, 3>>* facets) {
  auto strict = [](const Eigen::Vector3i& a, const Eigen::Vector3i& b, const Eigen::Vector3i& c) {
    return !(b - a).cross(c - b).isZero();
  };
  std::size_t n = ring.size();
  auto at = [&](std::size_t i, std::ptrdiff_t step) { return (i + n + static_cast<std::size_t>(n + step)) % n; };
  std::vector<bool> corner(n);
  int corners = 0;
  for (std::size_t i = 0; i < n; ++i) corners += (corner[i] = strict(points[at(i, -1)], points[i], points[at(i, 1)]));
  std::size_t k = 0;
  while (n > 3) {
    std::size_t tried = 0;
    for (;; k = at(k, 1), ++tried) {
      WAAM_DEMAND(tried <= n);
      if (!corner[k]) continue;
      const std::size_t p = at(k, -1), q = at(k, 1);
      const bool p_after = strict(points[at(p, -1)], points[p], points[q]);
      const bool q_after = strict(points[p], points[q], points[at(q, 1)]);
      const int left = corners - 1 - corner[p] - corner[q] + p_after + q_after;
      if (left < 3) continue;
      facets->push_back({ring[p], ring[k], ring[q]});
      corner[p] = p_after;
      corner[q] = q_after;
      corners = left;
      break;
    }
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
    points.erase(points.begin() + static_cast<std::ptrdiff_t>(k));
    corner.erase(corner.begin() + static_cast<std::ptrdiff_t>(k));
    --n;
    k %= n;
  }
  facets->push_back({ring[0], ring[1], ring[2]});
}

}  // namespace

planner::TriangleMesh ExtractVoxelSurface(const VoxelGrid& grid, std::size_t max_faces) {
  MeshOccupancy occ(grid);
  std::vector<Eigen::Vector3i> surface;
  if (!SurfaceVoxels(grid, &occ, max_faces, &surface)) return {};
  CheckInterrupt();
  // The exposed faces of the surface voxels (with the filled voxels counted as metal).
  std::vector<Face> faces;
  for (const Eigen::Vector3i& v : surface) {
    for (int d = 0; d < 6; ++d) {
      if (occ(v + kDirs[d])) continue;
      const int axis = d / 2;
      faces.push_back({d, v[axis] + (d % 2 == 0 ? 1 : 0), v[(axis + 2) % 3], v[(axis + 1) % 3]});
    }
  }
  if (faces.size() > max_faces) return {};
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());  // a voxel may be listed twice
  const std::vector<Quad> quads = MergeFaces(faces);
  std::vector<Face>().swap(faces);
  CheckInterrupt();

  // Every quad corner, sorted three ways, so that an edge along any axis finds the corners lying inside it.
  std::vector<Eigen::Vector3i> corners;
  corners.reserve(4 * quads.size());
  for (const Quad& q : quads) {
    const int axis = q.d / 2;
    for (int c = 0; c < 4; ++c) corners.push_back(Corner(axis, q.plane, c & 1 ? q.u1 + 1 : q.u0, c & 2 ? q.v1 + 1 : q.v0));
  }
  std::array<LineIndex, 3> lines;
  for (int a = 0; a < 3; ++a) {
    lines[a].axis = a;
    lines[a].corners = corners;
    std::sort(lines[a].corners.begin(), lines[a].corners.end(),
              [&](const Eigen::Vector3i& p, const Eigen::Vector3i& q) { return lines[a].Less(p, q); });
    lines[a].corners.erase(std::unique(lines[a].corners.begin(), lines[a].corners.end()), lines[a].corners.end());
  }
  std::vector<Eigen::Vector3i>().swap(corners);

  planner::TriangleMesh mesh;
  const double half_voxel = 0.5 * grid.voxel_mm();
  std::unordered_map<std::uint64_t, int> vertex_of;  // doubled corner coordinates -> vertex
  std::vector<Eigen::Vector3i> points;               // the vertices' doubled corner coordinates
  auto vertex = [&](const Eigen::Vector3i& doubled) {
    auto [it, inserted] = vertex_of.emplace(CellKey(doubled), static_cast<int>(points.size()));
    if (inserted) points.push_back(doubled);
    return it->second;
  };
  std::vector<int> ring;
  std::vector<Eigen::Vector3i> corner_points;  // the ring's points, doubled coordinates
  for (const Quad& q : quads) {
    const int axis = q.d / 2;
    // The rectangle's corners counter-clockwise seen from outside: e_(a+1) x e_(a+2) = e_a for the + faces.
    std::array<Eigen::Vector3i, 4> c = {Corner(axis, q.plane, q.u0, q.v0), Corner(axis, q.plane, q.u1 + 1, q.v0),
                                        Corner(axis, q.plane, q.u1 + 1, q.v1 + 1),
                                        Corner(axis, q.plane, q.u0, q.v1 + 1)};
    if (q.d % 2 == 1) std::swap(c[1], c[3]);
    ring.clear();
    corner_points.clear();
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3i& a = c[k];
      const Eigen::Vector3i& b = c[(k + 1) % 4];
      int along = 0;
      while (a[along] == b[along]) ++along;
      ring.push_back(vertex(2 * a));
      corner_points.push_back(2 * a);
      const LineIndex& line = lines[along];
      const auto less = [&](const Eigen::Vector3i& p, const Eigen::Vector3i& q) { return line.Less(p, q); };
      const Eigen::Vector3i& lo = a[along] < b[along] ? a : b;
      const Eigen::Vector3i& hi = a[along] < b[along] ? b : a;
      auto first = std::upper_bound(line.corners.begin(), line.corners.end(), lo, less);
      auto last = std::lower_bound(line.corners.begin(), line.corners.end(), hi, less);
      const std::size_t start = ring.size();
      for (auto it = first; it != last; ++it) {
        ring.push_back(vertex(2 * *it));
        corner_points.push_back(2 * *it);
      }
      if (a[along] > b[along]) {
        std::reverse(ring.begin() + static_cast<std::ptrdiff_t>(start), ring.end());
        std::reverse(corner_points.begin() + static_cast<std::ptrdiff_t>(start), corner_points.end());
      }
    }
    Triangulate(ring, corner_points, &mesh.facets);
  }
  CheckInterrupt();
  // The rectangles' corners inside a plane's region or on a straight crease are not needed: removed, so each plane's
  // region becomes one polygon (with holes) cut into triangles over the corners of its outline.
  RemoveFlatVertices(points, &mesh.facets);
  std::vector<int> renumbered(points.size(), -1);
  for (std::array<int, 3>& t : mesh.facets) {
    for (int& c : t) {
      int& id = renumbered[static_cast<std::size_t>(c)];
      if (id < 0) {
        id = static_cast<int>(mesh.vertices.size());
        mesh.vertices.push_back(points[static_cast<std::size_t>(c)].cast<double>() * half_voxel);
      }
      c = id;
    }
  }
  return mesh;
}

}  // namespace waam::twin
