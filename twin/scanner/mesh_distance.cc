// Point-to-mesh distance: median-split AABB tree, closest point on a triangle by Voronoi regions (Ericson,
// Real-Time Collision Detection 5.1.5), sign from angle-weighted pseudonormals (Baerentzen & Aanaes 2005).
#include "twin/scanner/mesh_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
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

}  // namespace

MeshDistance::MeshDistance(const planner::TriangleMesh& mesh) : mesh_(mesh) {
  WAAM_THROW_UNLESS(!mesh.facets.empty(), "mesh distance: the target mesh has no facets");
  const int nv = static_cast<int>(mesh.vertices.size());
  const std::size_t nf = mesh.facets.size();
  face_normal_.resize(nf);
  centroid_.resize(nf);
  edge_normal_.resize(nf);
  vertex_normal_.assign(mesh.vertices.size(), Eigen::Vector3d::Zero());
  std::map<std::pair<int, int>, Eigen::Vector3d> edge_sum;
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& t = mesh.facets[f];
    for (int k = 0; k < 3; ++k) {
      WAAM_THROW_UNLESS(t[k] >= 0 && t[k] < nv, "mesh distance: facet " << f << " refers to vertex " << t[k]
                                                                        << " of " << nv);
    }
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d& b = mesh.vertices[t[1]];
    const Eigen::Vector3d& c = mesh.vertices[t[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    face_normal_[f] = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitZ();
    centroid_[f] = (a + b + c) / 3.0;
    // Angle-weighted vertex normals.
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = mesh.vertices[t[k]];
      const Eigen::Vector3d e1 = mesh.vertices[t[(k + 1) % 3]] - p;
      const Eigen::Vector3d e2 = mesh.vertices[t[(k + 2) % 3]] - p;
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      vertex_normal_[t[k]] += angle * face_normal_[f];
      const std::pair<int, int> key(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
      // Eigen vectors are not zero-initialized: start each edge's sum explicitly.
      auto [it, inserted] = edge_sum.try_emplace(key, Eigen::Vector3d::Zero());
      it->second += face_normal_[f];
    }
  }
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& t = mesh.facets[f];
    for (int k = 0; k < 3; ++k) {
      edge_normal_[f][k] = edge_sum[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
    }
  }
  order_.resize(nf);
  for (std::size_t f = 0; f < nf; ++f) order_[f] = static_cast<int>(f);
  nodes_.reserve(2 * nf / 4 + 8);
  Build(0, static_cast<int>(nf));
}

int MeshDistance::Build(int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (int i = first; i < first + count; ++i) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = mesh_.vertices[mesh_.facets[order_[i]][k]];
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  nodes_[index].lo = lo;
  nodes_[index].hi = hi;
  if (count <= 4) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int mid = first + count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + first + count,
                   [&](int a, int b) { return centroid_[a][axis] < centroid_[b][axis]; });
  const int left = Build(first, mid - first);
  const int right = Build(mid, first + count - mid);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

double MeshDistance::SignedDistance(const Eigen::Vector3d& p, Eigen::Vector3d* closest) const {
  double best2 = std::numeric_limits<double>::infinity();
  Eigen::Vector3d best_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d best_normal = Eigen::Vector3d::UnitZ();
  std::vector<int> stack = {0};
  while (!stack.empty()) {
    const Node& node = nodes_[stack.back()];
    stack.pop_back();
    if (BoxDistance2(p, node.lo, node.hi) >= best2) continue;
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int f = order_[i];
        const auto& t = mesh_.facets[f];
        Feature feature;
        const Eigen::Vector3d q =
            ClosestOnTriangle(p, mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]], &feature);
        const double d2 = (p - q).squaredNorm();
        if (d2 >= best2) continue;
        best2 = d2;
        best_point = q;
        switch (feature) {
          case Feature::kFace: best_normal = face_normal_[f]; break;
          case Feature::kV0: best_normal = vertex_normal_[t[0]]; break;
          case Feature::kV1: best_normal = vertex_normal_[t[1]]; break;
          case Feature::kV2: best_normal = vertex_normal_[t[2]]; break;
          case Feature::kE01: best_normal = edge_normal_[f][0]; break;
          case Feature::kE12: best_normal = edge_normal_[f][1]; break;
          case Feature::kE20: best_normal = edge_normal_[f][2]; break;
        }
      }
      continue;
    }
    // Visit the nearer child first.
    const double dl = BoxDistance2(p, nodes_[node.left].lo, nodes_[node.left].hi);
    const double dr = BoxDistance2(p, nodes_[node.right].lo, nodes_[node.right].hi);
    if (dl < dr) {
      stack.push_back(node.right);
      stack.push_back(node.left);
    } else {
      stack.push_back(node.left);
      stack.push_back(node.right);
    }
  }
  if (closest != nullptr) *closest = best_point;
  const double d = std::sqrt(best2);
  return (p - best_point).dot(best_normal) >= 0.0 ? d : -d;
}

}  // namespace waam::twin
