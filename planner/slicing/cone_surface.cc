// Cone and cylinder surfaces of Dai et al. 2020: eq. 1, the equidistant surfaces of sec. 5 and the flattening of
// sec. 2.2 (the rotation by alpha before flattening and its inverse after mapping back).
#include "planner/slicing/cone_surface.h"

#include <cmath>

#include "models/core/numbers.h"

namespace waam::planner {
namespace {

double WrapPi(double a) {
  a = std::remainder(a, 2.0 * kPi);  // [-pi, pi]
  return a <= -kPi ? a + 2.0 * kPi : a;
}

}  // namespace

// k = R / H is the slope dr/dz of the generatrix with a minus sign: r(z) = R - k z (k = 0 for the cylinder).
double ConeSurface::RadiusAt(double z_P) const {
  const double z = z_P - axis_P.z();
  return cylinder() ? R : R * (1.0 - z / H);
}

double ConeSurface::Residual(const Eigen::Vector3d& p_P) const {
  const Eigen::Vector3d q = p_P - axis_P;
  const double r_surface = cylinder() ? R : R * (q.z() / H - 1.0);
  return q.x() * q.x() + q.y() * q.y() - r_surface * r_surface;  // eq. 1
}

double ConeSurface::NormalOffset(const Eigen::Vector3d& p_P) const {
  const Eigen::Vector3d q = p_P - axis_P;
  const double k = cylinder() ? 0.0 : R / H;
  // In the half-plane (r, z) of p the generatrix is the line r = R - k z; the distance to it is measured along
  // its normal (1, k) / sqrt(1 + k^2).
  return (std::hypot(q.x(), q.y()) - RadiusAt(p_P.z())) / std::sqrt(1.0 + k * k);
}

Eigen::Vector3d ConeSurface::Normal(const Eigen::Vector3d& p_P) const {
  const Eigen::Vector3d q = p_P - axis_P;
  const double k = cylinder() ? 0.0 : R / H;
  const double theta = std::atan2(q.y(), q.x());
  // Gradient of r - R (1 - z / H): (cos theta, sin theta, R / H).
  return Eigen::Vector3d(std::cos(theta), std::sin(theta), k).normalized();
}

ConeSurface ConeSurface::Offset(double d_mm) const {
  ConeSurface out = *this;
  if (cylinder()) {
    out.R = R + d_mm;
    return out;
  }
  // Sec. 5 of Dai: R_i = R + sqrt(1 + (R/H)^2) d i, H_i = H R_i / R (for R = 60, H = 200 the paper's
  // sqrt(109)/10 and sqrt(109)/3). Offsetting keeps the opening angle; the apex moves along the axis.
  const double k = R / H;
  out.R = R + std::sqrt(1.0 + k * k) * d_mm;
  out.H = H * out.R / R;
  return out;
}

double ConeSurface::Theta(const Eigen::Vector3d& p_P, double alpha) const {
  const Eigen::Vector3d q = p_P - axis_P;
  // The rotation matrix of sec. 2.2 (cos a, sin a; -sin a, cos a) turns a point by -alpha about the axis.
  return WrapPi(std::atan2(q.y(), q.x()) - alpha);
}

Eigen::Vector2d ConeSurface::Flatten(const Eigen::Vector3d& p_P, double alpha) const {
  const double theta = Theta(p_P, alpha);
  const double z = p_P.z() - axis_P.z();
  if (cylinder()) return Eigen::Vector2d(R * theta, z);
  // Sec. 2.2: theta_flat = R theta_0 / sqrt(R^2 + H^2); radius = slant distance from the apex,
  // sqrt((R (H - z) / H)^2 + (H - z)^2) = |H - z| sqrt(1 + k^2).
  const double k = R / H;
  const double slant = std::abs(H - z) * std::sqrt(1.0 + k * k);
  const double phi = theta * std::abs(k) / std::sqrt(1.0 + k * k);
  return slant * Eigen::Vector2d(std::cos(phi), std::sin(phi));
}

Eigen::Vector3d ConeSurface::Unflatten(const Eigen::Vector2d& q, double alpha) const {
  double theta = 0.0;
  double z = 0.0;
  double r = R;
  if (cylinder()) {
    theta = q.x() / R;
    z = q.y();
  } else {
    // The inverse mapping of sec. 2.2: theta_0 = sqrt(R^2 + H^2) / R atan2(y, x) and
    // z = H - H sqrt(x^2 + y^2) / sqrt(R^2 + H^2) (written here for either sign of H).
    const double k = R / H;
    const double root = std::sqrt(1.0 + k * k);
    const double slant = q.norm();
    theta = std::atan2(q.y(), q.x()) * root / std::abs(k);
    const double along = slant / root;  // distance from the apex along the axis
    z = H > 0.0 ? H - along : H + along;
    r = std::abs(k) * along;
  }
  theta += alpha;
  return axis_P + Eigen::Vector3d(r * std::cos(theta), r * std::sin(theta), z);
}

}  // namespace waam::planner
