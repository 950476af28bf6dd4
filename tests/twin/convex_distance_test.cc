// Tests of the GJK distance: closed-form distances between spheres, capsules, boxes, cylinders, a plane and a mesh
// hull, and the lower bound never above the distance.
#include "twin/cell/convex_distance.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace waam::twin {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

ConvexShape Shape(ConvexShape::Type type, const Vector3d& size, double rbound) {
  ConvexShape s;
  s.type = type;
  s.size_mm = size;
  s.rbound_mm = rbound;
  return s;
}

Isometry3d At(const Vector3d& p, const Eigen::AngleAxisd& r = Eigen::AngleAxisd(0.0, Vector3d::UnitZ())) {
  Isometry3d X = Isometry3d::Identity();
  X.translate(p);
  X.rotate(r);
  return X;
}

constexpr double kTol = 1e-3;

TEST(ConvexDistanceTest, ClosedFormsOfPrimitives) {
  const ConvexShape sphere = Shape(ConvexShape::Type::kSphere, {5, 0, 0}, 5);
  const ConvexShape capsule = Shape(ConvexShape::Type::kCapsule, {3, 20, 0}, 23);
  const ConvexShape box = Shape(ConvexShape::Type::kBox, {10, 20, 30}, std::sqrt(1400.0));
  const ConvexShape cylinder = Shape(ConvexShape::Type::kCylinder, {4, 10, 0}, std::sqrt(116.0));
  const ConvexShape plane = Shape(ConvexShape::Type::kPlane, {0, 0, 0}, 0);
  struct Case {
    const ConvexShape* a;
    Isometry3d X_WA;
    const ConvexShape* b;
    Isometry3d X_WB;
    double expected;
    const char* what;
  };
  const Case cases[] = {
      {&sphere, At({0, 0, 0}), &sphere, At({3, 4, 12}), 13.0 - 10.0, "sphere-sphere"},
      // Capsule along z at x = 0, sphere beside its middle: radial gap.
      {&capsule, At({0, 0, 0}), &sphere, At({20, 0, 5}), 20.0 - 3.0 - 5.0, "capsule-sphere side"},
      // Sphere above the capsule's end cap.
      {&capsule, At({0, 0, 0}), &sphere, At({0, 0, 40}), 40.0 - 20.0 - 3.0 - 5.0, "capsule-sphere cap"},
      // Box face to sphere, and the corner (10, 20, 30) to a sphere on the diagonal.
      {&box, At({0, 0, 0}), &sphere, At({0, 50, 0}), 50.0 - 20.0 - 5.0, "box face"},
      {&box, At({0, 0, 0}), &sphere, At(Vector3d(10, 20, 30) + Vector3d(1, 1, 1).normalized() * 15.0), 10.0,
       "box corner"},
      // Two boxes side by side, one turned 90 deg about z: half-sizes 20 along x after the turn.
      {&box, At({0, 0, 0}), &box, At({40, 0, 0}, Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitZ())), 40.0 - 10.0 - 20.0,
       "box-box turned"},
      // Cylinder lying along x above the plane z = 0: its lowest line at z - 4.
      {&plane, At({0, 0, 0}), &cylinder, At({7, -3, 12}, Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY())), 12.0 - 4.0,
       "plane-cylinder"},
      // Cylinder rim to a sphere beyond its edge, in the plane of the top face.
      {&cylinder, At({0, 0, 0}), &sphere, At({4 + 8, 0, 10}), 8.0 - 5.0, "cylinder rim"},
  };
  for (const Case& c : cases) {
    const ConvexDistance d = ShapeDistance(*c.a, c.X_WA, *c.b, c.X_WB, kTol);
    EXPECT_LE(d.lower_mm, c.expected + 1e-9) << c.what << ": the lower bound must not exceed the distance";
    EXPECT_NEAR(d.lower_mm, c.expected, kTol) << c.what;
    EXPECT_LE(BoundingSphereDistance(*c.a, c.X_WA, *c.b, c.X_WB), c.expected + 1e-9) << c.what;
  }
}

TEST(ConvexDistanceTest, OverlapGivesZero) {
  const ConvexShape box = Shape(ConvexShape::Type::kBox, {10, 10, 10}, std::sqrt(300.0));
  const ConvexDistance d = ShapeDistance(box, At({0, 0, 0}), box, At({15, 3, -2}), kTol);
  EXPECT_EQ(d.lower_mm, 0.0);
}

TEST(ConvexDistanceTest, MeshHullAgreesWithTheBoxItSpans) {
  ConvexShape cube = Shape(ConvexShape::Type::kMesh, {0, 0, 0}, std::sqrt(300.0));
  for (int i = 0; i < 8; ++i) cube.hull_mm.emplace_back(i & 1 ? 10 : -10, i & 2 ? 10 : -10, i & 4 ? 10 : -10);
  const ConvexShape box = Shape(ConvexShape::Type::kBox, {10, 10, 10}, std::sqrt(300.0));
  const ConvexShape capsule = Shape(ConvexShape::Type::kCapsule, {3, 20, 0}, 23);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Isometry3d X_WC = At(Vector3d(u(rng), u(rng), u(rng)) * 80.0,
                               Eigen::AngleAxisd(3.0 * u(rng), Vector3d(u(rng), u(rng), u(rng) + 2.0).normalized()));
    const Isometry3d X_WM = At(Vector3d(u(rng), u(rng), u(rng)) * 5.0,
                               Eigen::AngleAxisd(3.0 * u(rng), Vector3d(u(rng) + 2.0, u(rng), u(rng)).normalized()));
    const ConvexDistance mesh = ShapeDistance(cube, X_WM, capsule, X_WC, kTol);
    const ConvexDistance prim = ShapeDistance(box, X_WM, capsule, X_WC, kTol);
    EXPECT_NEAR(mesh.lower_mm, prim.lower_mm, 2 * kTol) << "trial " << trial;
    EXPECT_LE(mesh.lower_mm, mesh.upper_mm);
    EXPECT_LE(mesh.upper_mm - mesh.lower_mm, kTol + 1e-12);
  }
}

}  // namespace
}  // namespace waam::twin
