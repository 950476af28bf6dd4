// GJK distance between convex shapes with the separating-plane lower bound (Gilbert, Johnson, Keerthi 1988; the
// closest points of a simplex after Ericson, Real-Time Collision Detection, sec. 5.1.2, 5.1.5, 5.1.6).
#include "twin/cell/convex_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/error.h"

namespace waam::twin {
namespace {

using Eigen::Vector3d;

// A simplex of up to four points of the Minkowski difference A - B.
struct Simplex {
  Vector3d p[4] = {Vector3d::Zero(), Vector3d::Zero(), Vector3d::Zero(), Vector3d::Zero()};
  int n = 0;
};

Simplex Of(const Vector3d& a) {
  Simplex s;
  s.p[0] = a;
  s.n = 1;
  return s;
}
Simplex Of(const Vector3d& a, const Vector3d& b) {
  Simplex s = Of(a);
  s.p[1] = b;
  s.n = 2;
  return s;
}
Simplex Of(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  Simplex s = Of(a, b);
  s.p[2] = c;
  s.n = 3;
  return s;
}

// Closest point to the origin on segment ab (points by value: `s` may hold them); keeps in `s` the vertices of the feature it lies on.
Vector3d ClosestOnSegment(Vector3d a, Vector3d b, Simplex* s) {
  const Vector3d ab = b - a;
  const double t = -a.dot(ab);
  if (t <= 0.0) {
    *s = Of(a);
    return a;
  }
  const double len2 = ab.squaredNorm();
  if (t >= len2) {
    *s = Of(b);
    return b;
  }
  *s = Of(a, b);
  return a + ab * (t / len2);
}

// Closest point to the origin on triangle abc (Ericson 5.1.5, with the origin as the query point).
Vector3d ClosestOnTriangle(Vector3d a, Vector3d b, Vector3d c, Simplex* s) {
  const Vector3d ab = b - a, ac = c - a, ap = -a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    *s = Of(a);
    return a;
  }
  const Vector3d bp = -b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) {
    *s = Of(b);
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    *s = Of(a, b);
    return a + ab * (d1 / (d1 - d3));
  }
  const Vector3d cp = -c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) {
    *s = Of(c);
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    *s = Of(a, c);
    return a + ac * (d2 / (d2 - d6));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    *s = Of(b, c);
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double denom = 1.0 / (va + vb + vc);
  *s = Of(a, b, c);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Whether the origin and point d lie on opposite sides of the plane through a, b, c.
bool OriginOutsideFace(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) {
  const Vector3d n = (b - a).cross(c - a);
  const double sign_origin = -a.dot(n);
  const double sign_d = (d - a).dot(n);
  return sign_origin * sign_d < 0.0;
}

// Closest point to the origin on the simplex `s`, which is reduced to the smallest feature holding it. Returns the
// zero vector when the origin lies inside a tetrahedron.
Vector3d ClosestOnSimplex(Simplex* s) {
  switch (s->n) {
    case 1:
      return s->p[0];
    case 2:
      return ClosestOnSegment(s->p[0], s->p[1], s);
    case 3:
      return ClosestOnTriangle(s->p[0], s->p[1], s->p[2], s);
    default: {
      // Tetrahedron (Ericson 5.1.6): the closest of the faces the origin lies outside of.
      const Vector3d a = s->p[0], b = s->p[1], c = s->p[2], d = s->p[3];
      const Vector3d faces[4][4] = {{a, b, c, d}, {a, c, d, b}, {a, d, b, c}, {b, d, c, a}};
      double best = std::numeric_limits<double>::infinity();
      Vector3d closest = Vector3d::Zero();
      Simplex kept;
      bool outside = false;
      for (const auto& f : faces) {
        if (!OriginOutsideFace(f[0], f[1], f[2], f[3])) continue;
        outside = true;
        Simplex face;
        const Vector3d q = ClosestOnTriangle(f[0], f[1], f[2], &face);
        if (q.squaredNorm() < best) {
          best = q.squaredNorm();
          closest = q;
          kept = face;
        }
      }
      if (!outside) return Vector3d::Zero();
      *s = kept;
      return closest;
    }
  }
}

// Distance from the half-space z <= 0 of plane frame X_WP to shape b at X_WB (negative when it dips below), mm.
double PlaneDistance(const Eigen::Isometry3d& X_WP, const ConvexShape& b, const Eigen::Isometry3d& X_WB) {
  const Vector3d n_W = X_WP.linear().col(2);
  const Vector3d lowest_W = X_WB * b.Support(X_WB.linear().transpose() * -n_W);
  return n_W.dot(lowest_W - X_WP.translation());
}

}  // namespace

Vector3d ConvexShape::Support(const Vector3d& d) const {
  switch (type) {
    case Type::kSphere:
      return d * (size_mm[0] / d.norm());
    case Type::kCapsule:
      return Vector3d(0.0, 0.0, d.z() >= 0.0 ? size_mm[1] : -size_mm[1]) + d * (size_mm[0] / d.norm());
    case Type::kCylinder: {
      const double radial = std::hypot(d.x(), d.y());
      Vector3d p(0.0, 0.0, d.z() >= 0.0 ? size_mm[1] : -size_mm[1]);
      if (radial > 0.0) p.head<2>() = d.head<2>() * (size_mm[0] / radial);
      return p;
    }
    case Type::kBox:
      return Vector3d(d.x() >= 0.0 ? size_mm.x() : -size_mm.x(), d.y() >= 0.0 ? size_mm.y() : -size_mm.y(),
                      d.z() >= 0.0 ? size_mm.z() : -size_mm.z());
    case Type::kEllipsoid: {
      // The point of x^T D^-2 x = 1 whose normal is d: D^2 d / |D d|.
      const Vector3d Dd = size_mm.cwiseProduct(d);
      return size_mm.cwiseProduct(Dd) / Dd.norm();
    }
    case Type::kMesh: {
      WAAM_DEMAND(!hull_mm.empty());
      std::size_t best = 0;
      double best_dot = hull_mm[0].dot(d);
      for (std::size_t i = 1; i < hull_mm.size(); ++i) {
        const double dot = hull_mm[i].dot(d);
        if (dot > best_dot) {
          best_dot = dot;
          best = i;
        }
      }
      return hull_mm[best];
    }
    case Type::kPlane:
      break;
  }
  WAAM_DEMAND(false && "a plane has no support point");
  return Vector3d::Zero();
}

double BoundingSphereDistance(const ConvexShape& a, const Eigen::Isometry3d& X_WA, const ConvexShape& b,
                              const Eigen::Isometry3d& X_WB) {
  if (a.type == ConvexShape::Type::kPlane) {
    return X_WA.linear().col(2).dot(X_WB.translation() - X_WA.translation()) - b.rbound_mm;
  }
  if (b.type == ConvexShape::Type::kPlane) return BoundingSphereDistance(b, X_WB, a, X_WA);
  return (X_WA.translation() - X_WB.translation()).norm() - a.rbound_mm - b.rbound_mm;
}

ConvexDistance ShapeDistance(const ConvexShape& a, const Eigen::Isometry3d& X_WA, const ConvexShape& b,
                             const Eigen::Isometry3d& X_WB, double tolerance_mm) {
  WAAM_DEMAND(tolerance_mm > 0.0);
  WAAM_DEMAND(a.type != ConvexShape::Type::kPlane || b.type != ConvexShape::Type::kPlane);
  ConvexDistance result;
  if (a.type == ConvexShape::Type::kPlane || b.type == ConvexShape::Type::kPlane) {
    const double d = a.type == ConvexShape::Type::kPlane ? PlaneDistance(X_WA, b, X_WB) : PlaneDistance(X_WB, a, X_WA);
    result.lower_mm = std::max(0.0, d);
    result.upper_mm = result.lower_mm;
    return result;
  }
  const Eigen::Matrix3d R_AW = X_WA.linear().transpose();
  const Eigen::Matrix3d R_BW = X_WB.linear().transpose();
  // The support point of A - B along d (world frame).
  const auto support = [&](const Vector3d& d) {
    return Vector3d(X_WA * a.Support(R_AW * d) - X_WB * b.Support(R_BW * -d));
  };
  Simplex s;
  Vector3d v = X_WA.translation() - X_WB.translation();
  if (v.squaredNorm() == 0.0) v = Vector3d::UnitX();
  v = support(-v);
  s = Of(v);
  double lower = 0.0;
  constexpr int kMaxIterations = 64;
  for (int it = 0; it < kMaxIterations; ++it) {
    result.iterations = it + 1;
    const double v_norm = v.norm();
    if (v_norm <= 1e-12) {
      lower = 0.0;
      result.upper_mm = 0.0;
      break;
    }
    const Vector3d w = support(-v);
    // Every point x of A - B has x.v >= w.v: the plane normal to v through w separates the origin by w.v/|v|.
    lower = std::max(lower, w.dot(v) / v_norm);
    result.upper_mm = v_norm;
    if (v_norm - lower <= tolerance_mm) break;
    bool repeated = false;
    for (int i = 0; i < s.n; ++i) repeated = repeated || (s.p[i] - w).squaredNorm() < 1e-24;
    if (repeated) break;
    s.p[s.n++] = w;
    v = ClosestOnSimplex(&s);
  }
  result.lower_mm = std::max(0.0, lower);
  result.upper_mm = std::max(result.upper_mm, result.lower_mm);
  return result;
}

}  // namespace waam::twin
