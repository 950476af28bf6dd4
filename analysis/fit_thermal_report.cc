// `waam fit thermal`'s identifiability report: covariance, correlation and the least-determined combination of the
// free parameters from the Jacobian at the fitted point (no replay of its own).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "analysis/fit_internal.h"
#include "models/core/error.h"

namespace waam::analysis::internal {

namespace {

// The report over the parameters the window sees (a nonzero Jacobian column).
nlohmann::json SeenIdentifiability(const IdentifiabilityInput& in) {
  const std::size_t n = in.names.size();
  // Gauss-Newton's normal matrix in the scaled parameters x = value / scale; the prior adds W^2 to its diagonal.
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t r = 0; r < in.m; ++r) {
    const Eigen::Map<const Eigen::VectorXd> row(in.jacobian.data() + r * n, static_cast<Eigen::Index>(n));
    h.noalias() += row * row.transpose();
  }
  const Eigen::MatrixXd data_h = h;
  h.diagonal().array() += in.prior_weight * in.prior_weight;
  // Residual variance of one reading: s^2 = 2 cost / (m - n) (the data's part of the cost only).
  const double dof = static_cast<double>(in.m > n ? in.m - n : 1);
  const double s = std::sqrt(std::max(0.0, 2.0 * in.data_cost / dof));
  // Scale-free form D^-1/2 H D^-1/2 (unit diagonal): its eigenvalues do not depend on units; 1 - lambda_min is how
  // nearly two columns of the Jacobian are parallel. Its pseudo-inverse gives the covariance (a null direction,
  // lambda = 0, stays out and is reported as the undetermined combination).
  const auto norm_of = [](const Eigen::MatrixXd& a) {
    Eigen::VectorXd d = a.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
    return std::pair{Eigen::MatrixXd(d.asDiagonal() * a * d.asDiagonal()), d};
  };
  const auto [hn, d] = norm_of(h);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(hn);
  const Eigen::VectorXd lambda = eig.eigenvalues();  // ascending
  const double lmax = std::max(lambda(static_cast<Eigen::Index>(n) - 1), 1e-300);
  Eigen::MatrixXd inv = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(n); ++k) {
    if (lambda(k) > 1e-12 * lmax) inv += eig.eigenvectors().col(k) * eig.eigenvectors().col(k).transpose() / lambda(k);
  }
  const Eigen::MatrixXd cov_x = s * s * d.asDiagonal() * inv * d.asDiagonal();  // scaled parameters
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> data_eig(norm_of(data_h).first);

  nlohmann::json doc;
  doc["noise_c"] = s;
  doc["readings"] = in.m;
  doc["standard_deviation"] = nlohmann::json::object();
  doc["correlation"] = nlohmann::json::object();
  doc["undetermined"] = nlohmann::json::array();
  for (std::size_t i = 0; i < n; ++i) {
    const double sd = std::sqrt(std::max(0.0, cov_x(i, i))) * in.scales[i];
    doc["standard_deviation"][in.names[i]] = sd;
    for (std::size_t j = 0; j < n; ++j) {
      const double den = std::sqrt(std::max(0.0, cov_x(i, i) * cov_x(j, j)));
      doc["correlation"][in.names[i]][in.names[j]] = den > 0.0 ? cov_x(i, j) / den : (i == j ? 1.0 : 0.0);
    }
    // Not determined: one standard deviation is over kUndeterminedFraction of the value (of its scale near 0).
    if (sd > kUndeterminedFraction * std::max(std::abs(in.values[i]), 0.1 * in.scales[i])) {
      doc["undetermined"].push_back(in.names[i]);
    }
  }
  const double data_lmax = std::max(data_eig.eigenvalues()(static_cast<Eigen::Index>(n) - 1), 1e-300);
  doc["condition_number"] = data_lmax / std::max(data_eig.eigenvalues()(0), 1e-300 * data_lmax);
  // The least-determined combination: the data's weakest eigenvector, as a change of each parameter in its own
  // units, of one standard deviation along it (s / sqrt(lambda) in the normalised form), signed so that the first
  // parameter's change is positive.
  Eigen::VectorXd v = data_eig.eigenvectors().col(0);
  const Eigen::VectorXd dd = norm_of(data_h).second;
  const double lambda0 = std::max(data_eig.eigenvalues()(0), 1e-300 * data_lmax);
  if (v(0) < 0.0) v = -v;
  nlohmann::json weakest = nlohmann::json::object();
  for (std::size_t i = 0; i < n; ++i) {
    weakest[in.names[i]] = v(static_cast<Eigen::Index>(i)) * dd(static_cast<Eigen::Index>(i)) * in.scales[i] * s /
                           std::sqrt(lambda0);
  }
  doc["weakest"] = weakest;
  doc["prior_weight_c"] = in.prior_weight;
  return doc;
}

}  // namespace

nlohmann::json ThermalIdentifiability(const IdentifiabilityInput& in) {
  const std::size_t n = in.names.size();
  WAAM_DEMAND(n >= 1 && in.scales.size() == n && in.values.size() == n && in.jacobian.size() == in.m * n);
  // A parameter whose column is zero (not felt in the window) is blind: no figure.
  IdentifiabilityInput seen = in;
  seen.names.clear(), seen.scales.clear(), seen.values.clear(), seen.jacobian.clear();
  std::vector<std::size_t> cols;
  nlohmann::json blind = nlohmann::json::array();
  for (std::size_t k = 0; k < n; ++k) {
    double norm = 0.0;
    for (std::size_t r = 0; r < in.m; ++r) norm += in.jacobian[r * n + k] * in.jacobian[r * n + k];
    if (norm > 0.0) {
      cols.push_back(k), seen.names.push_back(in.names[k]), seen.scales.push_back(in.scales[k]);
      seen.values.push_back(in.values[k]);
    } else {
      blind.push_back(in.names[k]);
    }
  }
  for (std::size_t r = 0; r < in.m; ++r) {
    for (std::size_t k : cols) seen.jacobian.push_back(in.jacobian[r * n + k]);
  }
  nlohmann::json doc = cols.empty() ? nlohmann::json{{"standard_deviation", nlohmann::json::object()},
                                                     {"correlation", nlohmann::json::object()},
                                                     {"undetermined", nlohmann::json::array()},
                                                     {"weakest", nlohmann::json::object()},
                                                     {"condition_number", nullptr},
                                                     {"noise_c", nullptr},
                                                     {"readings", in.m},
                                                     {"prior_weight_c", in.prior_weight}}
                                    : SeenIdentifiability(seen);
  for (const auto& name : blind) doc["undetermined"].push_back(name);
  doc["blind"] = blind;
  return doc;
}

// The standard deviations, the strong correlations (|r| > 0.9), the weakest combination and what is undetermined.
void PrintIdentifiability(const nlohmann::json& id, double cell_mm, std::ostream& out) {
  if (id.is_null()) return;
  out << std::setprecision(3) << "  1 sd      ";
  for (const auto& [name, sd] : id["standard_deviation"].items()) out << " " << name << " " << sd.get<double>();
  std::ostringstream notes;
  notes << std::setprecision(3);
  if (id["noise_c"].is_number()) notes << "noise " << id["noise_c"].get<double>() << " degC";
  const nlohmann::json grid = id.value("jacobian_cell_mm", nlohmann::json());
  if (grid.is_number() && grid.get<double>() != cell_mm) {
    notes << (notes.tellp() > 0 ? "; " : "") << "Jacobian on the " << grid.get<double>() << " mm grid";
  }
  if (notes.tellp() > 0) out << " (" << notes.str() << ")";
  out << "\n";
  for (const auto& [a, row] : id["correlation"].items()) {
    for (const auto& [b, r] : row.items()) {
      if (a < b && std::abs(r.get<double>()) > 0.9) {
        out << "  correlated " << a << ", " << b << ": " << r.get<double>() << "\n";
      }
    }
  }
  if (id["condition_number"].is_number()) {
    out << "  weakest    condition " << id["condition_number"].get<double>() << ", 1 sd along:";
    for (const auto& [name, d] : id["weakest"].items()) out << " " << name << " " << std::showpos << d.get<double>();
    out << std::noshowpos << "\n";
  }
  for (const auto& name : id["undetermined"]) {
    out << "  note: the window does not determine " << name.get<std::string>() << " (1 sd over "
        << 100.0 * internal::kUndeterminedFraction << " % of its value): fix it (fewer --free) or add --prior\n";
  }
}

}  // namespace waam::analysis::internal
