// A vertical cone or cylinder x^2 + y^2 = R^2 (z/H - 1)^2 (Dai et al. 2020 eq. 1), its equidistant offsets, normals
// and the developable flattening onto the plane and back (Dai sec. 2.2).
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Core>

namespace waam::planner {

// A cone (finite H) or cylinder (H = +inf) about a vertical axis through `axis_P`, in the part frame P (mm).
// In the surface's own frame (origin at axis_P) the cone is x^2 + y^2 = R^2 (z/H - 1)^2 for z < H: radius R at
// z = 0, apex at z = H (H < 0 puts the apex below and the cone widens upwards). The cylinder is x^2 + y^2 = R^2.
struct ConeSurface {
  Eigen::Vector3d axis_P = Eigen::Vector3d::Zero();  // point on the axis where the radius is R, mm
  double R = 60.0;                                    // radius at axis_P, mm (> 0)
  double H = std::numeric_limits<double>::infinity(); // axis_P to the apex, mm (+inf: cylinder; nonzero)

  bool cylinder() const { return !std::isfinite(H); }
  // Radius of the surface at height z (part frame, mm).
  double RadiusAt(double z_P) const;
  // Residual of eq. 1 in the surface frame, x^2 + y^2 - R^2 (z/H - 1)^2 (mm^2); 0 on the surface.
  double Residual(const Eigen::Vector3d& p_P) const;
  // Signed distance along the surface normal (mm): > 0 on the side the normal points to (away from the axis).
  // Exact for points whose nearest surface point is on the nappe (not past the apex).
  double NormalOffset(const Eigen::Vector3d& p_P) const;
  // Unit normal pointing away from the axis, at the surface point nearest to p_P along its generatrix.
  Eigen::Vector3d Normal(const Eigen::Vector3d& p_P) const;
  // The equidistant surface at normal distance `d_mm` (Dai sec. 5: R_i = R + sqrt(1 + (R/H)^2) d,
  // H_i = H R_i / R; the cylinder: R_i = R + d). Same axis and opening angle.
  ConeSurface Offset(double d_mm) const;

  // Developable flattening (Dai sec. 2.2) of a point of the surface after turning it by -alpha about the axis
  // (the cutting line is the generatrix at angle pi). Cone: polar coordinates in the plane of the development,
  // radius = slant distance from the apex, angle = theta R / sqrt(R^2 + H^2). Cylinder: (R theta, z). mm, rad.
  // A point off the surface is flattened as its radial projection onto it (same theta and z).
  Eigen::Vector2d Flatten(const Eigen::Vector3d& p_P, double alpha) const;
  // The inverse of Flatten: a point of the plane back on the surface, turned by +alpha (mm).
  Eigen::Vector3d Unflatten(const Eigen::Vector2d& q, double alpha) const;
  // Angle about the axis of p_P after turning by -alpha, in (-pi, pi] (rad).
  double Theta(const Eigen::Vector3d& p_P, double alpha) const;
};

}  // namespace waam::planner
