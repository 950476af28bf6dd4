// Extrusion of planar regions with holes into closed, outward-oriented triangle meshes.
#include "planner/mesh/extrude.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/geometry/triangulate.h"

namespace waam::planner {
namespace {
}  // namespace

Ring CircleRing(const Eigen::Vector2d& center_mm, double radius_mm, int segments) {
  Ring ring;
  ring.reserve(segments);
  for (int i = 0; i < segments; ++i) {
    const double a = 2.0 * kPi * i / segments;
    ring.emplace_back(center_mm.x() + radius_mm * std::cos(a), center_mm.y() + radius_mm * std::sin(a));
  }
  return ring;
}

Ring RectangleRing(double x0, double y0, double x1, double y1) {
  return {Eigen::Vector2d(x0, y0), Eigen::Vector2d(x1, y0), Eigen::Vector2d(x1, y1), Eigen::Vector2d(x0, y1)};
}

void AppendMesh(const TriangleMesh& part, TriangleMesh* mesh) {
  const int offset = static_cast<int>(mesh->vertices.size());
  mesh->vertices.insert(mesh->vertices.end(), part.vertices.begin(), part.vertices.end());
  for (const std::array<int, 3>& f : part.facets) mesh->facets.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
}

TriangleMesh ExtrudeRegions(const std::vector<PolygonWithHoles>& regions, double z0_mm, double z1_mm) {
  WAAM_THROW_UNLESS(z1_mm > z0_mm, "extrusion from z = " << z0_mm << " mm to z = " << z1_mm << " mm: top must be above bottom");
  TriangleMesh mesh;
  for (const PolygonWithHoles& input : regions) {
    // Outer counter-clockwise and holes clockwise: the material is then on the left of every ring edge.
    PolygonWithHoles region = input;
    if (SignedArea(region.outer) < 0) std::reverse(region.outer.begin(), region.outer.end());
    for (Ring& hole : region.holes) {
      if (SignedArea(hole) > 0) std::reverse(hole.begin(), hole.end());
    }
    const std::vector<std::array<int, 3>> cap = TriangulateRegion(region);

    // Vertex k of the concatenated rings is 2k (bottom) and 2k + 1 (top).
    const int base = static_cast<int>(mesh.vertices.size());
    std::vector<const Ring*> rings = {&region.outer};
    for (const Ring& hole : region.holes) rings.push_back(&hole);
    int first = 0;
    for (const Ring* ring : rings) {
      const int n = static_cast<int>(ring->size());
      for (const Eigen::Vector2d& p : *ring) {
        mesh.vertices.emplace_back(p.x(), p.y(), z0_mm);
        mesh.vertices.emplace_back(p.x(), p.y(), z1_mm);
      }
      // Wall quad over edge a -> b: the outward normal is on the right of a -> b, i.e. (b - a) x z.
      for (int i = 0; i < n; ++i) {
        const int a = base + 2 * (first + i);
        const int b = base + 2 * (first + (i + 1) % n);
        mesh.facets.push_back({a, b, b + 1});
        mesh.facets.push_back({a, b + 1, a + 1});
      }
      first += n;
    }
    // Caps: the triangulation is counter-clockwise seen from +z, right for the top; the bottom is reversed.
    for (const std::array<int, 3>& t : cap) {
      mesh.facets.push_back({base + 2 * t[0] + 1, base + 2 * t[1] + 1, base + 2 * t[2] + 1});
      mesh.facets.push_back({base + 2 * t[0], base + 2 * t[2], base + 2 * t[1]});
    }
  }
  return mesh;
}

}  // namespace waam::planner
