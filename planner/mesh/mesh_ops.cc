// Welding, edge analysis and simple measures of indexed triangle meshes.
#include "planner/mesh/mesh_ops.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>

#include <Eigen/Geometry>

namespace waam::planner {
namespace {

// Mixes three cell coordinates into one hash key; different cells may share a key (their points are still
// compared by distance), so this only has to spread well.
std::uint64_t CellKey(std::int64_t i, std::int64_t j, std::int64_t k) {
  std::uint64_t h = static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull;
  h ^= static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
  h ^= static_cast<std::uint64_t>(k) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
  return h;
}

std::uint64_t BitsKey(const Eigen::Vector3d& p) {
  std::uint64_t bits[3];
  for (int a = 0; a < 3; ++a) {
    const double v = p[a] == 0.0 ? 0.0 : p[a];  // -0 and +0 weld together
    std::memcpy(&bits[a], &v, sizeof(double));
  }
  return CellKey(static_cast<std::int64_t>(bits[0]), static_cast<std::int64_t>(bits[1]),
                 static_cast<std::int64_t>(bits[2]));
}

// Undirected edge key (smaller vertex id in the high half) and the direction a facet runs it.
std::uint64_t EdgeKey(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

// splitmix64's finaliser: the low bits of a key, which pick a slot of the tables below, mixed from all of its bits.
std::uint64_t Mix(std::uint64_t h) {
  h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
  h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
  return h ^ (h >> 31);
}

// A map from 64-bit cell keys to vertex ids for at most `n` keys: open addressing with linear probing in two flat
// arrays (one cache miss a lookup, where std::unordered_map chases a node).
class CellTable {
 public:
  explicit CellTable(std::size_t n) {
    std::size_t capacity = 16;
    while (capacity < 2 * n) capacity *= 2;
    mask_ = capacity - 1;
    keys_.resize(capacity);
    ids_.assign(capacity, -1);
  }
  // The id stored for `key`, or null.
  int* Find(std::uint64_t key) {
    for (std::size_t slot = Mix(key) & mask_; ids_[slot] >= 0; slot = (slot + 1) & mask_) {
      if (keys_[slot] == key) return &ids_[slot];
    }
    return nullptr;
  }
  // The slot of `key`, holding `id` if the key was new (then true), else its id as it was (then false).
  std::pair<int*, bool> TryEmplace(std::uint64_t key, int id) {
    std::size_t slot = Mix(key) & mask_;
    for (; ids_[slot] >= 0; slot = (slot + 1) & mask_) {
      if (keys_[slot] == key) return {&ids_[slot], false};
    }
    keys_[slot] = key;
    ids_[slot] = id;
    return {&ids_[slot], true};
  }

 private:
  std::size_t mask_ = 0;
  std::vector<std::uint64_t> keys_;
  std::vector<int> ids_;
};

// The distinct points of `corners` (bit-identical coordinates, -0 and +0 alike) in first-seen order, and for each
// corner the index of its distinct point. An open-addressing table of 32-bit slots: a 1 M-facet STL repeats each
// point about six times, so this one pass leaves a sixth of the points to the tolerance grid.
std::vector<int> DistinctPoints(const std::vector<Eigen::Vector3d>& corners, std::vector<Eigen::Vector3d>* distinct) {
  std::size_t capacity = 16;
  while (capacity < 2 * corners.size()) capacity *= 2;
  std::vector<std::int32_t> slots(capacity, -1);
  std::vector<int> index_of(corners.size());
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const Eigen::Vector3d& p = corners[c];  // == holds for -0 and +0, and BitsKey maps both to one key
    if (!p.allFinite()) {  // never equal to anything, as in the tolerance search
      index_of[c] = static_cast<int>(distinct->size());
      distinct->push_back(p);
      continue;
    }
    std::size_t slot = Mix(BitsKey(p)) & (capacity - 1);
    while (slots[slot] >= 0 && (*distinct)[slots[slot]] != p) slot = (slot + 1) & (capacity - 1);
    if (slots[slot] < 0) {
      slots[slot] = static_cast<std::int32_t>(distinct->size());
      distinct->push_back(p);
    }
    index_of[c] = slots[slot];
  }
  return index_of;
}

// Welds points into the vertices of `mesh`: a point within the tolerance of a vertex (the lowest-numbered one) is
// that vertex, any other becomes a new one. Tolerance <= 0 welds bit-identical points only.
class VertexWelder {
 public:
  VertexWelder(double weld_tolerance_mm, std::size_t expected, TriangleMesh* mesh)
      : mesh_(mesh),
        head_(expected),
        exact_(weld_tolerance_mm <= 0.0),
        tol2_(weld_tolerance_mm * weld_tolerance_mm),
        inv_cell_(exact_ ? 0.0 : 0.5 / weld_tolerance_mm) {}

  int FindOrAdd(const Eigen::Vector3d& p) { return exact_ ? FindOrAddExact(p) : FindOrAddNear(p); }

 private:
  int FindOrAddExact(const Eigen::Vector3d& p) {
    int best = std::numeric_limits<int>::max();
    const int* last = head_.Find(BitsKey(p));
    for (int v = last == nullptr ? -1 : *last; v >= 0; v = next_[v]) {
      if (mesh_->vertices[v] == p) best = std::min(best, v);
    }
    if (best != std::numeric_limits<int>::max()) return best;
    return Add(BitsKey(p), p);
  }

  // Cells are 2 tol wide, so along each axis a point is within tol of its own cell and at most one neighbour:
  // 8 cells to search instead of 27.
  int FindOrAddNear(const Eigen::Vector3d& p) {
    int best = std::numeric_limits<int>::max();
    std::int64_t cell[3];
    std::int64_t other[3];
    for (int a = 0; a < 3; ++a) {
      // Clamped so the cast stays defined for absurd coordinates (points there simply share far cells).
      const double u = std::clamp(p[a] * inv_cell_, -1e15, 1e15);
      cell[a] = static_cast<std::int64_t>(std::floor(u));
      other[a] = u - static_cast<double>(cell[a]) < 0.5 ? cell[a] - 1 : cell[a] + 1;
    }
    for (int corner = 0; corner < 8; ++corner) {
      const int* last = head_.Find(CellKey(corner & 1 ? other[0] : cell[0], corner & 2 ? other[1] : cell[1],
                                           corner & 4 ? other[2] : cell[2]));
      if (last == nullptr) continue;
      for (int v = *last; v >= 0; v = next_[v]) {
        if (v < best && (mesh_->vertices[v] - p).squaredNorm() <= tol2_) best = v;
      }
    }
    if (best != std::numeric_limits<int>::max()) return best;
    return Add(CellKey(cell[0], cell[1], cell[2]), p);
  }

  // Adds `p` as a new vertex at the head of the list of cell `key`.
  int Add(std::uint64_t key, const Eigen::Vector3d& p) {
    const int id = static_cast<int>(mesh_->vertices.size());
    mesh_->vertices.push_back(p);
    auto [slot, inserted] = head_.TryEmplace(key, id);
    next_.push_back(inserted ? -1 : *slot);
    *slot = id;
    return id;
  }

  TriangleMesh* mesh_;
  CellTable head_;         // cell key -> last vertex inserted in that cell
  std::vector<int> next_;  // vertex -> previous vertex in the same cell list
  bool exact_;
  double tol2_;
  double inv_cell_;
};

// Removes the vertices no facet uses (ids keep their first-seen order).
void DropUnusedVertices(TriangleMesh* mesh) {
  std::vector<int> new_id(mesh->vertices.size(), -1);
  for (const std::array<int, 3>& f : mesh->facets) {
    for (int v : f) new_id[v] = 0;
  }
  int kept = 0;
  for (std::size_t v = 0; v < mesh->vertices.size(); ++v) {
    if (new_id[v] < 0) continue;
    new_id[v] = kept;
    mesh->vertices[kept++] = mesh->vertices[v];
  }
  mesh->vertices.resize(kept);
  for (std::array<int, 3>& f : mesh->facets) {
    for (int& v : f) v = new_id[v];
  }
}

}  // namespace

bool IsDegenerateFacet(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  if (longest2 == 0.0) return true;
  // |(b-a) x (c-a)| = 2 area; relative to the longest edge squared it is the sine of the flattest angle scale.
  return (b - a).cross(c - a).norm() <= 1e-12 * longest2;
}

TriangleMesh WeldTriangles(const std::vector<Eigen::Vector3d>& corners, double weld_tolerance_mm,
                           std::size_t* degenerate) {
  TriangleMesh mesh;
  // Bit-identical corners weld to the same vertex (the lowest within the tolerance of the first of them stays the
  // lowest: every vertex added later has a higher number), so each distinct point is looked up once, in the order
  // of its first corner: the same vertices, numbered the same, as looking up every corner.
  std::vector<Eigen::Vector3d> distinct;
  const std::vector<int> distinct_of = DistinctPoints(corners, &distinct);
  VertexWelder welder(weld_tolerance_mm, distinct.size(), &mesh);
  std::vector<int> vertex_of(distinct.size());
  for (std::size_t d = 0; d < distinct.size(); ++d) vertex_of[d] = welder.FindOrAdd(distinct[d]);

  std::size_t dropped = 0;
  mesh.facets.reserve(corners.size() / 3);
  for (std::size_t f = 0; f + 2 < corners.size(); f += 3) {
    const std::array<int, 3> ids = {vertex_of[distinct_of[f]], vertex_of[distinct_of[f + 1]],
                                    vertex_of[distinct_of[f + 2]]};
    if (ids[0] == ids[1] || ids[1] == ids[2] || ids[2] == ids[0] ||
        IsDegenerateFacet(mesh.vertices[ids[0]], mesh.vertices[ids[1]], mesh.vertices[ids[2]])) {
      ++dropped;
      continue;
    }
    mesh.facets.push_back(ids);
  }
  if (degenerate) *degenerate = dropped;
  if (dropped > 0) DropUnusedVertices(&mesh);  // vertices used only by dropped facets
  return mesh;
}

MeshReport InspectMesh(const TriangleMesh& mesh, double weld_tolerance_mm, const std::string& source) {
  MeshReport report;
  report.source = source;
  report.weld_tolerance_mm = weld_tolerance_mm;
  report.facets_read = mesh.facets.size();
  report.vertices = mesh.vertices.size();
  BoundingBox(mesh, &report.bbox_min, &report.bbox_max);

  // Each facet contributes its three edges with the direction it runs them; sorting groups the uses of an edge.
  std::vector<std::pair<std::uint64_t, bool>> edges;
  edges.reserve(mesh.facets.size() * 3);
  for (const std::array<int, 3>& f : mesh.facets) {
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0] ||
        IsDegenerateFacet(mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]])) {
      ++report.degenerate_facets;
    }
    for (int k = 0; k < 3; ++k) {
      const int a = f[k];
      const int b = f[(k + 1) % 3];
      edges.emplace_back(EdgeKey(a, b), a < b);
    }
  }
  report.facets = mesh.facets.size() - report.degenerate_facets;
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    const std::size_t count = j - i;
    if (count == 1) ++report.boundary_edges;
    if (count > 2) ++report.non_manifold_edges;
    if (count == 2 && edges[i].second == edges[i + 1].second) ++report.misoriented_edges;
    i = j;
  }
  report.watertight = !mesh.facets.empty() && report.boundary_edges == 0 && report.non_manifold_edges == 0;
  report.volume_mm3 = EnclosedVolume(mesh);
  return report;
}

void BoundingBox(const TriangleMesh& mesh, Eigen::Vector3d* min, Eigen::Vector3d* max) {
  if (mesh.vertices.empty()) {
    *min = Eigen::Vector3d::Zero();
    *max = Eigen::Vector3d::Zero();
    return;
  }
  *min = mesh.vertices.front();
  *max = mesh.vertices.front();
  for (const Eigen::Vector3d& v : mesh.vertices) {
    *min = min->cwiseMin(v);
    *max = max->cwiseMax(v);
  }
}

double EnclosedVolume(const TriangleMesh& mesh) {
  // Divergence theorem: V = (1/6) sum over facets of a . (b x c), each term a signed tetrahedron to the origin.
  // Points are taken relative to the first vertex to keep the sum well conditioned far from the origin.
  if (mesh.vertices.empty()) return 0.0;
  const Eigen::Vector3d o = mesh.vertices.front();
  double six_v = 0.0;
  for (const std::array<int, 3>& f : mesh.facets) {
    const Eigen::Vector3d a = mesh.vertices[f[0]] - o;
    const Eigen::Vector3d b = mesh.vertices[f[1]] - o;
    const Eigen::Vector3d c = mesh.vertices[f[2]] - o;
    six_v += a.dot(b.cross(c));
  }
  return six_v / 6.0;
}

double PlaceOnBuildPlate(TriangleMesh* mesh) {
  if (mesh->vertices.empty()) return 0.0;
  double z_min = mesh->vertices.front().z();
  for (const Eigen::Vector3d& v : mesh->vertices) z_min = std::min(z_min, v.z());
  Translate(mesh, Eigen::Vector3d(0.0, 0.0, -z_min));
  return -z_min;
}

void Translate(TriangleMesh* mesh, const Eigen::Vector3d& offset_mm) {
  for (Eigen::Vector3d& v : mesh->vertices) v += offset_mm;
}

}  // namespace waam::planner
