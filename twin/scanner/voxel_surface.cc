// Greedy meshing of the exposed voxel faces, with T-junctions split so that the surface stays closed.
#include "twin/scanner/voxel_surface.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "models/core/error.h"
#include "models/core/progress.h"
#include "twin/scanner/flat_vertices.h"
#include "twin/scanner/point_hash.h"
#include "twin/scanner/surface_mesh.h"

namespace waam::twin {
namespace {

// Occupancy for the mesh: the grid's metal (z >= 0; the substrate is air here) plus the voxels filled for manifoldness.
// Reads the grid's occupancy words through a one-block cache (the neighbours of a voxel are mostly in its block).
class MeshOccupancy {
 public:
  explicit MeshOccupancy(const VoxelGrid& grid) : grid_(grid) {}
  bool operator()(const Eigen::Vector3i& v) const {
    const Eigen::Vector3i origin(v.x() & ~kMask, v.y() & ~kMask, v.z() & ~kMask);
    if (origin != cached_origin_ || !cached_) {
      cached_ = true;
      cached_origin_ = origin;
      cached_grid_ = grid_.BlockAt(origin);
      const auto it = filled_.find(CellKey(origin / VoxelGrid::kBlock));
      cached_filled_ = it == filled_.end() ? nullptr : &it->second;
    }
    const int n = (v.x() & kMask) | (v.y() & kMask) << 3 | (v.z() & kMask) << 6;
    const std::uint64_t bit = std::uint64_t{1} << (n & 63);
    return (cached_grid_ != nullptr && ((*cached_grid_)[static_cast<std::size_t>(n >> 6)] & bit) != 0) ||
           (cached_filled_ != nullptr && ((*cached_filled_)[static_cast<std::size_t>(n >> 6)] & bit) != 0);
  }
  // Marks v filled; false when it already was.
  bool Fill(const Eigen::Vector3i& v) {
    const Eigen::Vector3i origin(v.x() & ~kMask, v.y() & ~kMask, v.z() & ~kMask);
    VoxelGrid::BlockBits& bits = filled_[CellKey(origin / VoxelGrid::kBlock)];
    cached_ = false;  // a block new to the map is not in the cache (the map's nodes themselves never move)
    const int n = (v.x() & kMask) | (v.y() & kMask) << 3 | (v.z() & kMask) << 6;
    std::uint64_t& word = bits[static_cast<std::size_t>(n >> 6)];
    const std::uint64_t bit = std::uint64_t{1} << (n & 63);
    const bool added = (word & bit) == 0;
    word |= bit;
    return added;
  }

 private:
  static constexpr int kMask = VoxelGrid::kBlock - 1;
  const VoxelGrid& grid_;
  std::unordered_map<std::uint64_t, VoxelGrid::BlockBits> filled_;  // block (CellKey of origin / kBlock) -> bits
  mutable bool cached_ = false;
  mutable Eigen::Vector3i cached_origin_ = Eigen::Vector3i::Zero();
  mutable const VoxelGrid::BlockBits* cached_grid_ = nullptr;
  mutable const VoxelGrid::BlockBits* cached_filled_ = nullptr;
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

// The quad corners sorted for the lines along one axis: by the two other coordinates, then the one along the axis
// (packed in one integer key, 21 bits each), so the corners on a line segment are one contiguous range. `id` is each
// corner's place in the index of axis 0, which numbers the distinct corners.
struct LineIndex {
  int axis;
  std::vector<std::uint64_t> keys;
  std::vector<std::uint32_t> id;
  std::uint64_t Key(const Eigen::Vector3i& p) const {
    return CellKey(Eigen::Vector3i(p[axis], p[(axis + 2) % 3], p[(axis + 1) % 3]));
  }
  Eigen::Vector3i Point(std::uint64_t key) const {  // the inverse of Key
    const Eigen::Vector3i c = CellOfKey(key);
    Eigen::Vector3i p;
    p[axis] = c.x();
    p[(axis + 2) % 3] = c.y();
    p[(axis + 1) % 3] = c.z();
    return p;
  }
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

// Every quad corner, sorted three ways, so that an edge along any axis finds the corners lying inside it.
std::array<LineIndex, 3> IndexCorners(const std::vector<Quad>& quads) {
  std::array<LineIndex, 3> lines;
  for (int a = 0; a < 3; ++a) {
    LineIndex& line = lines[static_cast<std::size_t>(a)];
    line.axis = a;
    line.keys.reserve(4 * quads.size());
    for (const Quad& q : quads) {
      for (int c = 0; c < 4; ++c) {
        line.keys.push_back(line.Key(Corner(q.d / 2, q.plane, c & 1 ? q.u1 + 1 : q.u0, c & 2 ? q.v1 + 1 : q.v0)));
      }
    }
    std::sort(line.keys.begin(), line.keys.end());
    line.keys.erase(std::unique(line.keys.begin(), line.keys.end()), line.keys.end());
  }
  // Ids through axis 0's order: a corner's key on axis a, re-packed for axis 0, found there.
  lines[0].id.resize(lines[0].keys.size());
  std::iota(lines[0].id.begin(), lines[0].id.end(), 0u);
  for (std::size_t a = 1; a < 3; ++a) {
    lines[a].id.resize(lines[a].keys.size());
    for (std::size_t i = 0; i < lines[a].keys.size(); ++i) {
      const std::uint64_t key = lines[0].Key(lines[a].Point(lines[a].keys[i]));
      const auto it = std::lower_bound(lines[0].keys.begin(), lines[0].keys.end(), key);
      lines[a].id[i] = static_cast<std::uint32_t>(it - lines[0].keys.begin());
    }
  }
  return lines;
}

// The exposed faces of the surface voxels (with the filled voxels counted as metal), sorted, each once.
std::vector<Face> ExposedFaceList(const std::vector<Eigen::Vector3i>& surface, const MeshOccupancy& occ,
                                  std::size_t max_faces) {
  std::vector<Face> faces;
  for (const Eigen::Vector3i& v : surface) {
    for (int d = 0; d < 6; ++d) {
      if (occ(v + kDirs[d])) continue;
      const int axis = d / 2;
      faces.push_back({d, v[axis] + (d % 2 == 0 ? 1 : 0), v[(axis + 2) % 3], v[(axis + 1) % 3]});
    }
  }
  if (faces.size() > max_faces) return faces;
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());  // a voxel may be listed twice
  return faces;
}

// The mesh's vertices, numbered in the order the rectangles first use them (the order RemoveFlatVertices visits
// them), and each rectangle's ring of corners.
class QuadRings {
 public:
  explicit QuadRings(const std::array<LineIndex, 3>& lines) : lines_(lines), vertex_of_(lines[0].keys.size(), -1) {}

  // The ring of rectangle `q` counter-clockwise seen from outside, with every corner of a neighbouring rectangle
  // that lies on its edges: vertex ids into `ring`, their doubled coordinates into `corner_points`.
  void Ring(const Quad& q, std::vector<int>* ring, std::vector<Eigen::Vector3i>* corner_points) {
    const int axis = q.d / 2;
    // The rectangle's corners counter-clockwise seen from outside: e_(a+1) x e_(a+2) = e_a for the + faces.
    std::array<Eigen::Vector3i, 4> c = {Corner(axis, q.plane, q.u0, q.v0), Corner(axis, q.plane, q.u1 + 1, q.v0),
                                        Corner(axis, q.plane, q.u1 + 1, q.v1 + 1),
                                        Corner(axis, q.plane, q.u0, q.v1 + 1)};
    if (q.d % 2 == 1) std::swap(c[1], c[3]);
    ring->clear();
    corner_points->clear();
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3i& a = c[static_cast<std::size_t>(k)];
      const Eigen::Vector3i& b = c[static_cast<std::size_t>((k + 1) % 4)];
      int along = 0;
      while (a[along] == b[along]) ++along;
      const LineIndex& line = lines_[static_cast<std::size_t>(along)];
      const bool forward = a[along] < b[along];
      // The corners strictly between a and b, in order from a.
      const auto first = std::upper_bound(line.keys.begin(), line.keys.end(), line.Key(forward ? a : b));
      const auto last = std::lower_bound(first, line.keys.end(), line.Key(forward ? b : a));
      const auto at_a = forward ? first - 1 : last;
      ring->push_back(Vertex(line.id[static_cast<std::size_t>(at_a - line.keys.begin())], a));
      corner_points->push_back(2 * a);
      const std::size_t start = ring->size();
      for (auto it = first; it != last; ++it) {
        const Eigen::Vector3i p = line.Point(*it);
        ring->push_back(Vertex(line.id[static_cast<std::size_t>(it - line.keys.begin())], p));
        corner_points->push_back(2 * p);
      }
      if (!forward) {
        std::reverse(ring->begin() + static_cast<std::ptrdiff_t>(start), ring->end());
        std::reverse(corner_points->begin() + static_cast<std::ptrdiff_t>(start), corner_points->end());
      }
    }
  }

  // The vertices' doubled corner coordinates.
  const std::vector<Eigen::Vector3i>& points() const { return points_; }

 private:
  int Vertex(std::uint32_t corner, const Eigen::Vector3i& p) {
    int& id = vertex_of_[corner];
    if (id < 0) {
      id = static_cast<int>(points_.size());
      points_.push_back(2 * p);
    }
    return id;
  }

  const std::array<LineIndex, 3>& lines_;
  std::vector<int> vertex_of_;  // corner id -> vertex
  std::vector<Eigen::Vector3i> points_;
};

// Keeps only the vertices `mesh`'s facets use (doubled corner coordinates `points`, scaled by `half_voxel` mm), in
// the order the facets first use them.
void KeepUsedVertices(const std::vector<Eigen::Vector3i>& points, double half_voxel, planner::TriangleMesh* mesh) {
  std::vector<int> renumbered(points.size(), -1);
  for (std::array<int, 3>& t : mesh->facets) {
    for (int& c : t) {
      int& id = renumbered[static_cast<std::size_t>(c)];
      if (id < 0) {
        id = static_cast<int>(mesh->vertices.size());
        mesh->vertices.push_back(points[static_cast<std::size_t>(c)].cast<double>() * half_voxel);
      }
      c = id;
    }
  }
}

}  // namespace

planner::TriangleMesh ExtractVoxelSurface(const VoxelGrid& grid, std::size_t max_faces) {
  if (ExposedFaces(grid) > max_faces) return {};  // counted on the occupancy bits, without building anything
  MeshOccupancy occ(grid);
  std::vector<Eigen::Vector3i> surface;
  if (!SurfaceVoxels(grid, &occ, max_faces, &surface)) return {};
  CheckInterrupt();
  std::vector<Face> faces = ExposedFaceList(surface, occ, max_faces);
  if (faces.size() > max_faces) return {};
  const std::vector<Quad> quads = MergeFaces(faces);
  std::vector<Face>().swap(faces);
  CheckInterrupt();

  const std::array<LineIndex, 3> lines = IndexCorners(quads);
  planner::TriangleMesh mesh;
  QuadRings rings(lines);
  std::vector<int> ring;
  std::vector<Eigen::Vector3i> corner_points;  // the ring's points, doubled coordinates
  for (const Quad& q : quads) {
    rings.Ring(q, &ring, &corner_points);
    Triangulate(ring, corner_points, &mesh.facets);
  }
  CheckInterrupt();
  // The rectangles' corners inside a plane's region or on a straight crease are not needed: removed, so each plane's
  // region becomes one polygon (with holes) cut into triangles over the corners of its outline.
  RemoveFlatVertices(rings.points(), &mesh.facets);
  KeepUsedVertices(rings.points(), 0.5 * grid.voxel_mm(), &mesh);
  return mesh;
}

}  // namespace waam::twin
