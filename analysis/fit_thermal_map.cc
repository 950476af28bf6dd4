// `waam fit thermal`'s smooth maps from Ceres' unbounded variables to the bounded thermal parameters, and the cap
// on Ceres' steps in those variables.
#include <algorithm>
#include <cmath>
#include <vector>

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

// Ceres' steps in u, each coordinate capped at +-kMaxFreeStep (Plus; its Jacobian at delta = 0 is the identity on the
// free coordinates). Near a lower bound dx/du is small, so the linearisation in u asks steps of hundreds of units (a
// factor e^100 in x) that the trust region, scaled by the Jacobian's columns, does not hold back: the cap takes the
// step part of the way, and the next Jacobian, from a point where dx/du is larger, goes on. The values themselves
// are never clamped. Held coordinates (a parameter held at a bound) are not in the tangent space: they stay as they
// are.
class CappedStep final : public ceres::Manifold {
 public:
  CappedStep(int n, const std::vector<bool>& held) : n_(n) {
    for (int k = 0; k < n; ++k) {
      if (k >= static_cast<int>(held.size()) || !held[k]) free_.push_back(k);
    }
  }
  int AmbientSize() const override { return n_; }
  int TangentSize() const override { return static_cast<int>(free_.size()); }
  bool Plus(const double* u, const double* delta, double* out) const override {
    std::copy(u, u + n_, out);
    for (std::size_t j = 0; j < free_.size(); ++j) {
      out[free_[j]] = u[free_[j]] + std::clamp(delta[j], -kMaxFreeStep, kMaxFreeStep);
    }
    return true;
  }
  bool PlusJacobian(const double*, double* jacobian) const override {  // n x free, row-major
    std::fill(jacobian, jacobian + n_ * free_.size(), 0.0);
    for (std::size_t j = 0; j < free_.size(); ++j) jacobian[free_[j] * free_.size() + j] = 1.0;
    return true;
  }
  bool Minus(const double* y, const double* u, double* delta) const override {
    for (std::size_t j = 0; j < free_.size(); ++j) delta[j] = y[free_[j]] - u[free_[j]];
    return true;
  }
  bool MinusJacobian(const double*, double* jacobian) const override {  // free x n, row-major
    std::fill(jacobian, jacobian + free_.size() * n_, 0.0);
    for (std::size_t j = 0; j < free_.size(); ++j) jacobian[j * n_ + free_[j]] = 1.0;
    return true;
  }

 private:
  int n_;
  std::vector<int> free_;  // the coordinates in the tangent space
};

}  // namespace

ceres::Manifold* NewCappedStep(int n, const std::vector<bool>& held) {
  WAAM_DEMAND(std::count(held.begin(), held.end(), true) < n);
  return new CappedStep(n, held);
}

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
