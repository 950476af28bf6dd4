// `waam fit thermal`'s smooth maps from Ceres' unbounded variables to the bounded thermal parameters.
#include <algorithm>
#include <cmath>

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

}  // namespace

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
