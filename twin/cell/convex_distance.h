// Distance between two convex shapes by GJK on their support functions, with a certified lower bound: the
// continuous cell check (twin/cell/cell_sweep.h) steps on it. MuJoCo-free; the shapes are MuJoCo's geoms.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace waam::twin {

// A convex collision shape in its own frame G, after MuJoCo's geom conventions (a mesh stands for its convex hull,
// as in MuJoCo's collision detection).
struct ConvexShape {
  enum class Type { kPlane, kSphere, kCapsule, kCylinder, kBox, kEllipsoid, kMesh };
  Type type = Type::kSphere;
  // sphere: radius; capsule, cylinder: radius, half-length along z; box: half-sizes; ellipsoid: semi-axes; mm
  Eigen::Vector3d size_mm = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> hull_mm;  // mesh: the vertices of its convex hull in G, mm
  // mesh: its triangles as MuJoCo loaded them, in G (mm; three vertex indices into mesh_mm each), for peers that
  // collide the triangles themselves (tools/peers/fcl_check.cc); the distance queries use the hull.
  std::vector<Eigen::Vector3d> mesh_mm;
  std::vector<std::array<int, 3>> faces;
  double rbound_mm = 0.0;                // radius of a sphere about G's origin holding the shape (0 for a plane), mm

  // The point of the shape farthest along `dir_G` (any length, not zero), in G, mm. A plane has none (WAAM_DEMAND).
  Eigen::Vector3d Support(const Eigen::Vector3d& dir_G) const;
};

// What a distance query found.
struct ConvexDistance {
  double lower_mm = 0.0;  // certified: no two points of the shapes are closer (0 when they touch or overlap), mm
  double upper_mm = 0.0;  // the distance between two points of the shapes GJK found (>= lower_mm), mm
  int iterations = 0;     // GJK iterations (0 for a plane or a bounding-sphere answer)
};

// Distance between shape `a` at pose X_WA and shape `b` at X_WB (mm). GJK (Gilbert, Johnson, Keerthi 1988) on the
// Minkowski difference A - B stops when the gap between the closest simplex point |v| and the separating-plane bound
// v.w/|v| (w the support of A - B along -v) is below `tolerance_mm` (> 0); lower_mm is that bound, so it never
// overstates the distance. A plane is the half-space z <= 0 of its frame: the distance is the other shape's lowest
// point above it. Two planes: WAAM_DEMAND.
ConvexDistance ShapeDistance(const ConvexShape& a, const Eigen::Isometry3d& X_WA, const ConvexShape& b,
                             const Eigen::Isometry3d& X_WB, double tolerance_mm);

// Lower bound on the distance from the two shapes' bounding spheres (a plane: from its half-space), mm; may be
// negative.
double BoundingSphereDistance(const ConvexShape& a, const Eigen::Isometry3d& X_WA, const ConvexShape& b,
                              const Eigen::Isometry3d& X_WB);

}  // namespace waam::twin
