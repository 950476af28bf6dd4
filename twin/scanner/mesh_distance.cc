// Point-to-mesh distance: median-split AABB tree, closest point on a triangle by Voronoi regions (Ericson,
// Real-Time Collision Detection 5.1.5), sign from angle-weighted pseudonormals (Baerentzen & Aanaes 2005).
#include "twin/scanner/mesh_distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include <Eigen/Geometry>

#include "models/core/error.h"

namespace waam::twin {
namespace {

// Which feature of the triangle the closest point lies on.
enum class Feature { kFace, kV0, kV1, kV2, kE01, kE12, kE20 };

Eigen::Vector3d ClosestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c, Feature* feature) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return *feature = Feature::kV0, a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return *feature = Feature::kV1, b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return *feature = Feature::kE01, a + ab * (d1 / (d1 - d3));
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return *feature = Feature::kV2, c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return *feature = Feature::kE20, a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return *feature = Feature::kE12, b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double denom = 1.0 / (va + vb + vc);
  *feature = Feature::kFace;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double BoxDistance2(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const Eigen::Vector3d d = (lo - p).cwiseMax(p - hi).cwiseMax(Eigen::Vector3d::Zero());
  return d.squaredNorm();
}

// Inner nodes of the hierarchy Build() makes over `count` facets (leaves of at most 4).
std::size_t InnerNodes(std::size_t count) {
  return count <= 4 ? 0 : 1 + InnerNodes(count / 2) + InnerNodes(count - count / 2);
}

}  // namespace

// Memory: a voxel part's surface has ~10^7 facets (part III of the tubes), so per facet only the facet order of the
// tree is kept, and the boxes of the inner nodes; the normals of the one closest feature of a query are recomputed,
// the facets around its vertex found through the tree, rather than held in a map of edges and per-facet normal
// tables, which on a part of that size would take gigabytes.
MeshDistance::MeshDistance(const planner::TriangleMesh& mesh) : mesh_(mesh) {
  WAAM_THROW_UNLESS(!mesh.facets.empty(), "mesh distance: the target mesh has no facets");
  const int nv = static_cast<int>(mesh.vertices.size());
  const std::size_t nf = mesh.facets.size();
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& t = mesh.facets[f];
    for (int k = 0; k < 3; ++k) {
      WAAM_THROW_UNLESS(t[k] >= 0 && t[k] < nv, "mesh distance: facet " << f << " refers to vertex " << t[k]
                                                                        << " of " << nv);
    }
  }
  order_.resize(nf);
  for (std::size_t f = 0; f < nf; ++f) order_[f] = static_cast<int>(f);
  nodes_.reserve(InnerNodes(nf));
  Build(0, static_cast<int>(nf));
}

void MeshDistance::RangeBox(int first, int count, Eigen::Vector3d* lo, Eigen::Vector3d* hi) const {
  *lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  *hi = -*lo;
  for (int i = first; i < first + count; ++i) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = mesh_.vertices[mesh_.facets[order_[i]][k]];
      *lo = lo->cwiseMin(p);
      *hi = hi->cwiseMax(p);
    }
  }
}

int MeshDistance::Build(int first, int count) {
  if (count <= 4) return -1;  // a leaf
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::Vector3d lo, hi;
  RangeBox(first, count, &lo, &hi);
  nodes_[index].lo = lo;
  nodes_[index].hi = hi;
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int mid = first + count / 2;
  // Split at the median facet centroid along the box's longest axis. The centroid coordinate is computed in each
  // comparison (a table of centroids would be 24 bytes a facet, 0.3 GB on part III at the peak of the build).
  auto centroid = [&](int f) {
    const auto& t = mesh_.facets[f];
    return (mesh_.vertices[t[0]][axis] + mesh_.vertices[t[1]][axis] + mesh_.vertices[t[2]][axis]) / 3.0;
  };
  std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + first + count,
                   [&](int a, int b) { return centroid(a) < centroid(b); });
  Build(first, mid - first);  // an inner left child is index + 1
  nodes_[index].right = Build(mid, first + count - mid);
  return index;
}

Eigen::Vector3d MeshDistance::FaceNormal(int f) const {
  const auto& t = mesh_.facets[f];
  const Eigen::Vector3d& a = mesh_.vertices[t[0]];
  const Eigen::Vector3d& b = mesh_.vertices[t[1]];
  const Eigen::Vector3d& c = mesh_.vertices[t[2]];
  const Eigen::Vector3d n = (b - a).cross(c - a);
  return n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitZ();
}

void MeshDistance::FacetsAt(int v, std::vector<int>* facets) const {
  facets->clear();
  const Eigen::Vector3d& x = mesh_.vertices[v];
  auto has_v = [&](int f) {
    const auto& t = mesh_.facets[f];
    return t[0] == v || t[1] == v || t[2] == v;
  };
  struct Range {
    int node, first, count;
  };
  std::array<Range, 128> stack;
  int top = 0;
  stack[top++] = {nodes_.empty() ? -1 : 0, 0, static_cast<int>(order_.size())};
  while (top > 0) {
    const Range r = stack[--top];
    if (r.node < 0) {
      for (int i = r.first; i < r.first + r.count; ++i) {
        if (has_v(order_[i])) facets->push_back(order_[i]);
      }
      continue;
    }
    const Node& node = nodes_[r.node];
    if ((x.array() < node.lo.array()).any() || (x.array() > node.hi.array()).any()) continue;
    const int mid = r.first + r.count / 2;
    stack[top++] = {mid - r.first > 4 ? r.node + 1 : -1, r.first, mid - r.first};
    stack[top++] = {node.right, mid, r.first + r.count - mid};
  }
  std::sort(facets->begin(), facets->end());
}

Eigen::Vector3d MeshDistance::VertexNormal(int v) const {
  // Angle-weighted: each facet's normal times its angle at v, summed in facet order.
  std::vector<int> facets;
  FacetsAt(v, &facets);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const int f : facets) {
    const auto& t = mesh_.facets[f];
    const Eigen::Vector3d n = FaceNormal(f);
    for (int k = 0; k < 3; ++k) {
      if (t[k] != v) continue;
      const Eigen::Vector3d& p = mesh_.vertices[t[k]];
      const Eigen::Vector3d e1 = mesh_.vertices[t[(k + 1) % 3]] - p;
      const Eigen::Vector3d e2 = mesh_.vertices[t[(k + 2) % 3]] - p;
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      sum += angle * n;
    }
  }
  return sum;
}

Eigen::Vector3d MeshDistance::EdgeNormal(int a, int b) const {
  // The normals of the facets with edge (a, b), either direction, in facet order.
  std::vector<int> facets;
  FacetsAt(a, &facets);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const int lo = std::min(a, b), hi = std::max(a, b);
  for (const int f : facets) {
    const auto& t = mesh_.facets[f];
    for (int k = 0; k < 3; ++k) {
      if (std::min(t[k], t[(k + 1) % 3]) == lo && std::max(t[k], t[(k + 1) % 3]) == hi) sum += FaceNormal(f);
    }
  }
  return sum;
}

std::size_t MeshDistance::MemoryBytes() const {
  return nodes_.capacity() * sizeof(Node) + order_.capacity() * sizeof(int);
}

double MeshDistance::SignedDistance(const Eigen::Vector3d& p, Eigen::Vector3d* closest) const {
  double best2 = std::numeric_limits<double>::infinity();
  Eigen::Vector3d best_point = Eigen::Vector3d::Zero();
  int best_facet = -1;
  Feature best_feature = Feature::kFace;
  // A subtree to visit: its node (-1 for a leaf), its range of order_ and the squared distance to its box.
  struct Pending {
    int node, first, count;
    double box2;
  };
  auto pending = [&](int node, int first, int count) {
    if (node >= 0) return Pending{node, first, count, BoxDistance2(p, nodes_[node].lo, nodes_[node].hi)};
    Eigen::Vector3d lo, hi;
    RangeBox(first, count, &lo, &hi);
    return Pending{node, first, count, BoxDistance2(p, lo, hi)};
  };
  // Depth-first: at most one pending right sibling per level, and the tree is ~log2(facets / 4) deep.
  std::array<Pending, 128> stack;
  int top = 0;
  const int facets = static_cast<int>(order_.size());
  stack[top++] = pending(nodes_.empty() ? -1 : 0, 0, facets);
  while (top > 0) {
    const Pending e = stack[--top];
    if (e.box2 >= best2) continue;
    if (e.node < 0) {
      for (int i = e.first; i < e.first + e.count; ++i) {
        const int f = order_[i];
        const auto& t = mesh_.facets[f];
        Feature feature;
        const Eigen::Vector3d q =
            ClosestOnTriangle(p, mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]], &feature);
        const double d2 = (p - q).squaredNorm();
        if (d2 >= best2) continue;
        best2 = d2;
        best_point = q;
        best_facet = f;
        best_feature = feature;
      }
      continue;
    }
    // Visit the nearer child first.
    const int mid = e.first + e.count / 2;
    const Pending left = pending(mid - e.first > 4 ? e.node + 1 : -1, e.first, mid - e.first);
    const Pending right = pending(nodes_[e.node].right, mid, e.first + e.count - mid);
    if (left.box2 < right.box2) {
      stack[top++] = right;
      stack[top++] = left;
    } else {
      stack[top++] = left;
      stack[top++] = right;
    }
  }
  Eigen::Vector3d best_normal = Eigen::Vector3d::UnitZ();
  if (best_facet >= 0) {
    const auto& t = mesh_.facets[best_facet];
    switch (best_feature) {
      case Feature::kFace: best_normal = FaceNormal(best_facet); break;
      case Feature::kV0: best_normal = VertexNormal(t[0]); break;
      case Feature::kV1: best_normal = VertexNormal(t[1]); break;
      case Feature::kV2: best_normal = VertexNormal(t[2]); break;
      case Feature::kE01: best_normal = EdgeNormal(t[0], t[1]); break;
      case Feature::kE12: best_normal = EdgeNormal(t[1], t[2]); break;
      case Feature::kE20: best_normal = EdgeNormal(t[2], t[0]); break;
    }
  }
  if (closest != nullptr) *closest = best_point;
  const double d = std::sqrt(best2);
  return (p - best_point).dot(best_normal) >= 0.0 ? d : -d;
}

}  // namespace waam::twin
