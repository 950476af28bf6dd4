// `waam fit thermal`'s smooth maps from Ceres' unbounded variables to the bounded thermal parameters, and the cap
// on Ceres' steps in those variables.
#include <algorithm>
#include <cmath>

#include <ceres/manifold.h>

#include "analysis/fit_internal.h"
#include "models/core/error.h"

namespace waam::analysis::internal {

namespace {

// The logistic 1 / (1 + exp(-u)), in a form that overflows for neither sign of u.
double Logistic(double u) {
  if (u >= 0.0) return 1.0 / (1.0 + std::exp(-u));
  const double e = std::exp(u);
  return e / (1.0 + e);
}

// Ceres' steps in u, each coordinate capped at +-kMaxFreeStep (Plus; its Jacobian at delta = 0 is the identity). Near
// a lower bound dx/du is small, so the linearisation in u asks steps of hundreds of units (a factor e^100 in x) that
// the trust region, scaled by the Jacobian's columns, does not hold back: the cap takes the step part of the way, and
// the next Jacobian, from a point where dx/du is larger, goes on. The values themselves are never clamped.
class CappedStep final : public ceres::Manifold {
 public:
  explicit CappedStep(int n) : n_(n) {}
  int AmbientSize() const override { return n_; }
  int TangentSize() const override { return n_; }
  bool Plus(const double* u, const double* delta, double* out) const override {
    for (int k = 0; k < n_; ++k) out[k] = u[k] + std::clamp(delta[k], -kMaxFreeStep, kMaxFreeStep);
    return true;
  }
  bool PlusJacobian(const double*, double* jacobian) const override { return Identity(jacobian); }
  bool Minus(const double* y, const double* u, double* delta) const override {
    for (int k = 0; k < n_; ++k) delta[k] = y[k] - u[k];
    return true;
  }
  bool MinusJacobian(const double*, double* jacobian) const override { return Identity(jacobian); }

 private:
  bool Identity(double* jacobian) const {
    std::fill(jacobian, jacobian + n_ * n_, 0.0);
    for (int k = 0; k < n_; ++k) jacobian[k * n_ + k] = 1.0;
    return true;
  }
  int n_;
};

}  // namespace

ceres::Manifold* NewCappedStep(int n) { return new CappedStep(n); }

double ParameterMap::ToScaled(double u) const {
  if (std::isinf(hi)) return lo + std::exp(u);
  return lo + (hi - lo) * Logistic(u);
}

double ParameterMap::ToFree(double x) const {
  WAAM_DEMAND(!std::isnan(x) && lo < hi);
  if (std::isinf(hi)) return std::log(std::max(x, lo + kStartInside) - lo);
  // Inside by kStartInside, or by a quarter of the range when that is narrower.
  const double inside = std::min(kStartInside, 0.25 * (hi - lo));
  const double clamped = std::clamp(x, lo + inside, hi - inside);
  return std::log((clamped - lo) / (hi - clamped));
}

double ParameterMap::Slope(double u) const {
  if (std::isinf(hi)) return std::exp(u);
  const double s = Logistic(u);
  return (hi - lo) * s * (1.0 - s);
}

}  // namespace waam::analysis::internal
