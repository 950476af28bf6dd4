// Greedy meshing of the exposed voxel faces, with T-junctions split so that the surface stays closed.
#include "twin/scanner/voxel_surface.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "models/core/progress.h"
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

// Greedy rectangles of one plane's faces (sorted by v, u): from the first face not yet taken, the longest run along
// u, then as many following rows as hold that whole run untaken. Appends the rectangles to `quads`.
void MergePlane(const Face* faces, std::size_t count, std::vector<Quad>* quads) {
  auto key = [](int u, int v) {
    return static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 32 | static_cast<std::uint32_t>(v);
  };
  std::unordered_set<std::uint64_t> free;  // faces not yet in a rectangle
  free.reserve(count);
  for (std::size_t i = 0; i < count; ++i) free.insert(key(faces[i].u, faces[i].v));
  for (std::size_t i = 0; i < count; ++i) {
    const Face& f = faces[i];
    if (free.erase(key(f.u, f.v)) == 0) continue;
    int u1 = f.u;
    while (free.erase(key(u1 + 1, f.v)) != 0) ++u1;
    int v1 = f.v;
    for (;;) {
      bool whole = true;
      for (int u = f.u; u <= u1 && whole; ++u) whole = free.count(key(u, v1 + 1)) != 0;
      if (!whole) break;
      ++v1;
      for (int u = f.u; u <= u1; ++u) free.erase(key(u, v1));
    }
    quads->push_back({f.d, f.plane, f.u, u1, f.v, v1});
  }
}

// The rectangles of every plane of `faces` (sorted by d, plane, v, u): each plane merged with rows along u and along
// v, keeping the fewer rectangles.
std::vector<Quad> MergeFaces(const std::vector<Face>& faces) {
  std::vector<Quad> quads, by_u, by_v;
  std::vector<Face> swapped;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i;
    while (j < faces.size() && faces[j].d == faces[i].d && faces[j].plane == faces[i].plane) ++j;
    by_u.clear();
    by_v.clear();
    MergePlane(&faces[i], j - i, &by_u);
    swapped.assign(faces.begin() + static_cast<std::ptrdiff_t>(i), faces.begin() + static_cast<std::ptrdiff_t>(j));
    for (Face& f : swapped) std::swap(f.u, f.v);
    std::sort(swapped.begin(), swapped.end());
    MergePlane(swapped.data(), swapped.size(), &by_v);
    if (by_v.size() < by_u.size()) {
      for (Quad& q : by_v) {
        std::swap(q.u0, q.v0);
        std::swap(q.u1, q.v1);
      }
      quads.insert(quads.end(), by_v.begin(), by_v.end());
    } else {
      quads.insert(quads.end(), by_u.begin(), by_u.end());
    }
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
  auto vertex = [&](const Eigen::Vector3i& doubled) {
    auto [it, inserted] = vertex_of.emplace(CellKey(doubled), static_cast<int>(mesh.vertices.size()));
    if (inserted) mesh.vertices.push_back(doubled.cast<double>() * half_voxel);
    return it->second;
  };
  std::vector<int> ring;
  std::vector<bool> is_corner;
  for (const Quad& q : quads) {
    const int axis = q.d / 2;
    // The rectangle's corners counter-clockwise seen from outside: e_(a+1) x e_(a+2) = e_a for the + faces.
    std::array<Eigen::Vector3i, 4> c = {Corner(axis, q.plane, q.u0, q.v0), Corner(axis, q.plane, q.u1 + 1, q.v0),
                                        Corner(axis, q.plane, q.u1 + 1, q.v1 + 1),
                                        Corner(axis, q.plane, q.u0, q.v1 + 1)};
    if (q.d % 2 == 1) std::swap(c[1], c[3]);
    ring.clear();
    is_corner.clear();
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3i& a = c[k];
      const Eigen::Vector3i& b = c[(k + 1) % 4];
      int along = 0;
      while (a[along] == b[along]) ++along;
      ring.push_back(vertex(2 * a));
      is_corner.push_back(true);
      const LineIndex& line = lines[along];
      const auto less = [&](const Eigen::Vector3i& p, const Eigen::Vector3i& q) { return line.Less(p, q); };
      const Eigen::Vector3i& lo = a[along] < b[along] ? a : b;
      const Eigen::Vector3i& hi = a[along] < b[along] ? b : a;
      auto first = std::upper_bound(line.corners.begin(), line.corners.end(), lo, less);
      auto last = std::lower_bound(line.corners.begin(), line.corners.end(), hi, less);
      const std::size_t start = ring.size();
      for (auto it = first; it != last; ++it) {
        ring.push_back(vertex(2 * *it));
        is_corner.push_back(false);
      }
      if (a[along] > b[along]) std::reverse(ring.begin() + start, ring.end());
    }
    // Fan from a rectangle corner whose two edges are not split (n - 2 triangles, none degenerate), else from the
    // rectangle's centre (n triangles).
    const int n = static_cast<int>(ring.size());
    int apex = -1;
    for (int k = 0; k < n && apex < 0; ++k) {
      if (is_corner[k] && is_corner[(k + 1) % n] && is_corner[(k + n - 1) % n]) apex = k;
    }
    if (apex >= 0) {
      for (int k = 1; k + 1 < n; ++k) mesh.facets.push_back({ring[apex], ring[(apex + k) % n], ring[(apex + k + 1) % n]});
    } else {
      const int centre = vertex(c[0] + c[2]);
      for (int k = 0; k < n; ++k) mesh.facets.push_back({centre, ring[k], ring[(k + 1) % n]});
    }
  }
  return mesh;
}

}  // namespace waam::twin
