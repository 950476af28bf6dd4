// Void-length network (dissertation sec. 4.4.2.2, eq. 4.7, Fig. 33): forward pass, Ceres training with an L2
// penalty and optional Bayesian (MacKay evidence) update of the penalty, JSON.
#include "models/voids/void_length_network.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include <Eigen/Dense>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "models/core/error.h"
#include "models/core/progress.h"
#include "models/fit/internal/ceres_solve.h"
#include "models/fit/model_file.h"

namespace waam::models {
namespace {

constexpr char kModelName[] = "void_length";
using std::tanh;  // ceres::tanh for Jets is found by ADL

// Forward pass: weights are stored layer by layer, each as a row-major (out x in) matrix followed by out biases.
template <typename T>
T Forward(const std::vector<int>& sizes, const T* w, const std::vector<double>& x) {
  // Two reused per-thread buffers: this runs once per sample and residual evaluation, on Jets during training.
  thread_local std::vector<T> buffer_a, buffer_b;
  const int widest = *std::max_element(sizes.begin(), sizes.end());
  if (static_cast<int>(buffer_a.size()) < widest) {
    buffer_a.resize(widest);
    buffer_b.resize(widest);
  }
  T* a = buffer_a.data();
  T* next = buffer_b.data();
  for (std::size_t i = 0; i < x.size(); ++i) a[i] = T(x[i]);
  const T* p = w;
  for (std::size_t l = 0; l + 1 < sizes.size(); ++l) {
    const int in = sizes[l], out = sizes[l + 1];
    const bool hidden = l + 2 < sizes.size();
    for (int o = 0; o < out; ++o) {
      T sum = p[in * out + o];  // bias
      for (int i = 0; i < in; ++i) sum += p[o * in + i] * a[i];
      next[o] = hidden ? tanh(sum) : sum;  // tanh hidden layers, linear output
    }
    p += in * out + out;
    std::swap(a, next);
  }
  return a[0];
}

double Normalise(double v, double lo, double hi) { return hi > lo ? 2.0 * (v - lo) / (hi - lo) - 1.0 : 0.0; }

// Normalised residual of every training sample: net(x_i) - y_i. One block for all samples keeps Ceres' per-block
// overhead out of the inner loop.
struct SamplesResidual {
  const std::vector<int>* sizes;
  const std::vector<std::vector<double>>* x;  // normalised inputs
  const std::vector<double>* y;               // normalised targets
  template <typename T>
  bool operator()(T const* const* w, T* residual) const {
    for (std::size_t i = 0; i < y->size(); ++i) residual[i] = Forward(*sizes, w[0], (*x)[i]) - T((*y)[i]);
    return true;
  }
};

// sqrt(l2) * w_j for every weight: the L2 penalty as residuals.
struct PenaltyResidual {
  int num_weights;
  double sqrt_l2;
  template <typename T>
  bool operator()(T const* const* w, T* residual) const {
    for (int j = 0; j < num_weights; ++j) residual[j] = sqrt_l2 * w[0][j];
    return true;
  }
};

constexpr int kStride = 32;

// One training run from one initialisation. Returns the solver report; `weights` holds the result. When
// `bayesian`, the penalty weight is re-estimated from the evidence (MacKay 1992; MATLAB trainbr) between solves.
struct RunResult {
  SolverReport report;
  double l2 = 0.0;
  double effective_params = 0.0;  // gamma = sum s_i / (s_i + l2) over the eigenvalues s_i of J^T J
  double objective = 0.0;         // sum r^2 + l2 sum w^2 (normalised units)
};

RunResult TrainOnce(const std::vector<int>& sizes, const std::vector<std::vector<double>>& x,
                    const std::vector<double>& y, double l2, bool bayesian, int max_iterations,
                    std::vector<double>* weights) {
  const int num_weights = static_cast<int>(weights->size());
  const int n = static_cast<int>(y.size());
  RunResult result;
  result.l2 = l2;
  const int outer = bayesian ? 4 : 1;
  for (int round = 0; round < outer; ++round) {
    ceres::Problem problem;
    std::vector<ceres::ResidualBlockId> data_blocks;
    auto* data_cost =
        new ceres::DynamicAutoDiffCostFunction<SamplesResidual, kStride>(new SamplesResidual{&sizes, &x, &y});
    data_cost->AddParameterBlock(num_weights);
    data_cost->SetNumResiduals(n);
    data_blocks.push_back(problem.AddResidualBlock(data_cost, nullptr, weights->data()));
    auto* penalty = new ceres::DynamicAutoDiffCostFunction<PenaltyResidual, kStride>(
        new PenaltyResidual{num_weights, std::sqrt(result.l2)});
    penalty->AddParameterBlock(num_weights);
    penalty->SetNumResiduals(num_weights);
    problem.AddResidualBlock(penalty, nullptr, weights->data());
    // Network training stops at a relative cost change of 1e-7: tighter only polishes noise-level digits.
    ceres::Solver::Options solver_options = internal::DefaultSolverOptions(max_iterations);
    solver_options.function_tolerance = 1e-7;
    solver_options.parameter_tolerance = 1e-8;
    solver_options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;  // J^T J is 106 x 106 and damped by LM

    result.report = internal::Solve(solver_options, &problem);
    if (!result.report.usable) return result;

    // Jacobian of the data residuals at the solution -> effective number of parameters gamma.
    ceres::Problem::EvaluateOptions eval;
    eval.residual_blocks = data_blocks;
    double cost = 0.0;
    std::vector<double> residuals;
    ceres::CRSMatrix crs;
    problem.Evaluate(eval, &cost, &residuals, nullptr, &crs);
    Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
    for (int r = 0; r < crs.num_rows; ++r) {
      for (int k = crs.rows[r]; k < crs.rows[r + 1]; ++k) jac(r, crs.cols[k]) = crs.values[k];
    }
    const Eigen::VectorXd s = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(jac.transpose() * jac).eigenvalues();
    double gamma = 0.0;
    for (int i = 0; i < s.size(); ++i) gamma += std::max(s[i], 0.0) / (std::max(s[i], 0.0) + result.l2);
    double ed = 0.0, ew = 0.0;
    for (double r : residuals) ed += r * r;
    for (double w : *weights) ew += w * w;
    result.effective_params = gamma;
    result.objective = ed + result.l2 * ew;
    // MacKay's update: alpha = gamma / (2 E_W), beta = (n - gamma) / (2 E_D); the penalty weight is alpha / beta.
    if (bayesian && round + 1 < outer && ew > 0.0 && n > gamma && ed > 0.0) {
      result.l2 = std::clamp(gamma * ed / ((n - gamma) * ew), 1e-8, 1e2);
    }
  }
  return result;
}

}  // namespace

void VoidNetworkOptions::Validate() const {
  WAAM_THROW_UNLESS(!hidden.empty() && hidden.size() <= 4, "void-length network: " << hidden.size()
                                                                                  << " hidden layers: must be 1 to 4");
  for (int h : hidden) {
    WAAM_THROW_UNLESS(h >= 1 && h <= 64, "void-length network: hidden layer of " << h << " neurons: must be 1 to 64");
  }
  WAAM_THROW_UNLESS(std::isfinite(l2) && l2 >= 0.0, "void-length network: l2 = " << l2 << ": must be >= 0");
  WAAM_THROW_UNLESS(restarts >= 1 && restarts <= 1000,
                    "void-length network: restarts = " << restarts << ": must be 1 to 1000");
  WAAM_THROW_UNLESS(max_iterations >= 1, "void-length network: max_iterations = " << max_iterations << ": must be >= 1");
}

std::vector<double> NetworkInputs(const Junction& junction, AngleOrder order) {
  std::array<double, 4> a = junction.angles_deg;
  if (order == AngleOrder::kSortedDescending) std::sort(a.begin(), a.end(), std::greater<>());
  return {static_cast<double>(junction.turning_points), a[0], a[1], a[2], a[3]};
}

int VoidLengthNetwork::NumWeights(const std::vector<int>& sizes) {
  int count = 0;
  for (std::size_t l = 0; l + 1 < sizes.size(); ++l) count += sizes[l] * sizes[l + 1] + sizes[l + 1];
  return count;
}

VoidLengthNetwork::VoidLengthNetwork(std::vector<int> layer_sizes, std::vector<std::vector<double>> members,
                                     std::vector<double> input_min, std::vector<double> input_max, double output_min,
                                     double output_max, AngleOrder order, FitInfo fit, nlohmann::json training)
    : layer_sizes_(std::move(layer_sizes)),
      members_(std::move(members)),
      input_min_(std::move(input_min)),
      input_max_(std::move(input_max)),
      output_min_(output_min),
      output_max_(output_max),
      order_(order),
      fit_(std::move(fit)),
      training_(std::move(training)) {}

double VoidLengthNetwork::PredictMm(const Junction& junction) const {
  std::vector<double> x = NetworkInputs(junction, order_);
  for (int i = 0; i < kInputs; ++i) x[i] = Normalise(x[i], input_min_[i], input_max_[i]);
  double y = 0.0;
  for (const std::vector<double>& w : members_) y += Forward(layer_sizes_, w.data(), x);
  y /= static_cast<double>(members_.size());
  return output_min_ + (y + 1.0) * 0.5 * (output_max_ - output_min_);
}

nlohmann::json VoidLengthNetwork::ToJson() const {
  nlohmann::json j;
  j["model"] = kModelName;
  j["format_version"] = kModelFormatVersion;
  j["kind"] = "network";
  j["formula"] = "L = net(eta, theta1, theta2, theta3, theta4): inputs and output mapped to [-1, 1] by min/max, "
                 "tanh hidden layers, linear output";
  j["source"] = "Nguyen 2022 dissertation, sec. 4.4.2.2, eq. 4.7, Appendix A1";
  j["params"] = {{"layer_sizes", layer_sizes_},
                 {"members", members_},
                 {"input_min", input_min_},
                 {"input_max", input_max_},
                 {"output_min", output_min_},
                 {"output_max", output_max_},
                 {"angle_order", order_}};
  j["units"] = {{"eta", "count"}, {"theta", "deg"}, {"L", "mm"}};
  j["training"] = training_;
  j["fit"] = waam::models::ToJson(fit_);
  return j;
}

VoidLengthNetwork VoidLengthNetwork::FromJson(const nlohmann::json& j, const std::string& where) {
  const nlohmann::json::json_pointer params("/params");
  WAAM_THROW_UNLESS(j.contains(params) && j.at(params).is_object(), where << ": /params is missing");
  const nlohmann::json& p = j.at(params);
  std::vector<int> sizes;
  std::vector<std::vector<double>> members;
  std::vector<double> in_min, in_max;
  try {
    sizes = p.at("layer_sizes").get<std::vector<int>>();
    members = p.at("members").get<std::vector<std::vector<double>>>();
    in_min = p.at("input_min").get<std::vector<double>>();
    in_max = p.at("input_max").get<std::vector<double>>();
  } catch (const nlohmann::json::exception& e) {
    WAAM_THROW(where << ": /params: layer_sizes, members, input_min and input_max must be number arrays ("
                     << e.what() << ")");
  }
  WAAM_THROW_UNLESS(sizes.size() >= 3 && sizes.front() == kInputs && sizes.back() == 1,
                    where << ": /params/layer_sizes must be [5, hidden..., 1]");
  for (int s : sizes) WAAM_THROW_UNLESS(s >= 1, where << ": /params/layer_sizes must be positive");
  WAAM_THROW_UNLESS(!members.empty(), where << ": /params/members is empty");
  for (std::size_t k = 0; k < members.size(); ++k) {
    WAAM_THROW_UNLESS(static_cast<int>(members[k].size()) == NumWeights(sizes),
                      where << ": /params/members/" << k << " has " << members[k].size()
                            << " weights, layer_sizes need " << NumWeights(sizes));
  }
  WAAM_THROW_UNLESS(in_min.size() == kInputs && in_max.size() == kInputs,
                    where << ": /params/input_min and input_max need 5 values");
  const std::string order = p.value("angle_order", "as_given");
  const std::optional<AngleOrder> angle_order = ParseEnum<AngleOrder>(order);
  WAAM_THROW_UNLESS(angle_order, where << ": /params/angle_order '" << order << "': must be "
                                       << EnumNameList<AngleOrder>(" or "));
  return VoidLengthNetwork(sizes, members, in_min, in_max, JsonNumber(j, "/params/output_min", where),
                           JsonNumber(j, "/params/output_max", where),
                           *angle_order,
                           FitInfoFromJson(j, where), j.value("training", nlohmann::json()));
}

namespace {

// Training inputs and targets mapped to [-1, 1] by their min/max over the samples (MATLAB mapminmax).
struct NormalisedSamples {
  std::vector<double> in_min, in_max;
  double out_min = INFINITY, out_max = -INFINITY;
  std::vector<std::vector<double>> x;
  std::vector<double> y;
};

NormalisedSamples NormaliseSamples(const std::vector<JunctionSample>& samples, AngleOrder order) {
  const int n = static_cast<int>(samples.size());
  NormalisedSamples d;
  d.in_min.assign(VoidLengthNetwork::kInputs, INFINITY);
  d.in_max.assign(VoidLengthNetwork::kInputs, -INFINITY);
  for (const JunctionSample& s : samples) {
    const std::vector<double> x = NetworkInputs(s.junction, order);
    for (int k = 0; k < VoidLengthNetwork::kInputs; ++k) {
      d.in_min[k] = std::min(d.in_min[k], x[k]);
      d.in_max[k] = std::max(d.in_max[k], x[k]);
    }
    d.out_min = std::min(d.out_min, s.void_length_mm);
    d.out_max = std::max(d.out_max, s.void_length_mm);
  }
  if (!(d.out_max > d.out_min)) d.out_max = d.out_min + 1.0;  // constant target: any scale works
  d.x.resize(n);
  d.y.resize(n);
  for (int i = 0; i < n; ++i) {
    d.x[i] = NetworkInputs(samples[i].junction, order);
    for (int k = 0; k < VoidLengthNetwork::kInputs; ++k) d.x[i][k] = Normalise(d.x[i][k], d.in_min[k], d.in_max[k]);
    d.y[i] = Normalise(samples[i].void_length_mm, d.out_min, d.out_max);
  }
  return d;
}

// Seeded initial weights of one restart: LeCun-uniform weights (unit-variance pre-activations for inputs in
// [-1, 1]), small biases.
std::vector<double> InitialWeights(const std::vector<int>& sizes, unsigned long long seed, int restart) {
  std::seed_seq seq{seed, static_cast<unsigned long long>(restart)};
  std::mt19937_64 rng(seq);
  std::vector<double> w(VoidLengthNetwork::NumWeights(sizes));
  std::size_t k = 0;
  for (std::size_t l = 0; l + 1 < sizes.size(); ++l) {
    const double a = std::sqrt(3.0 / sizes[l]);
    std::uniform_real_distribution<double> weight(-a, a), bias(-0.1, 0.1);
    for (int i = 0; i < sizes[l] * sizes[l + 1]; ++i) w[k++] = weight(rng);
    for (int i = 0; i < sizes[l + 1]; ++i) w[k++] = bias(rng);
  }
  return w;
}

// What the seeded restarts gave: the best run and its weights, every usable run's weights, the log.
struct Restarts {
  RunResult best;
  std::vector<double> best_weights;  // empty when no restart was usable
  std::vector<std::vector<double>> usable_weights;
  double gamma_sum = 0.0;  // sum of the usable runs' effective parameter counts
  nlohmann::json log = nlohmann::json::array();
  std::string last_failure;  // the last unusable restart's Ceres message
};

Restarts RunRestarts(const std::vector<int>& sizes, const NormalisedSamples& d, const VoidNetworkOptions& options,
                     bool bayesian) {
  Restarts r;
  for (int restart = 0; restart < options.restarts; ++restart) {
    CheckInterrupt();
    std::vector<double> w = InitialWeights(sizes, options.seed, restart);
    const RunResult run = TrainOnce(sizes, d.x, d.y, options.l2, bayesian, options.max_iterations, &w);
    r.log.push_back({{"restart", restart}, {"usable", run.report.usable}, {"objective", run.objective},
                     {"l2", run.l2}, {"iterations", run.report.iterations}});
    if (!run.report.usable) {
      r.last_failure = "restart " + std::to_string(restart) + ": Ceres " +
                       std::string(NameOf(run.report.termination)) + ": " + run.report.message;
      continue;
    }
    r.usable_weights.push_back(w);
    r.gamma_sum += run.effective_params;
    if (r.best_weights.empty() || run.objective < r.best.objective) {
      r.best = run;
      r.best_weights = w;
    }
  }
  return r;
}

}  // namespace

VoidNetworkFit TrainVoidLengthNetwork(const std::vector<JunctionSample>& samples, const DataSource& data,
                                      const VoidNetworkOptions& options) {
  options.Validate();
#ifdef __GLIBC__
  // Ceres allocates and frees the dense normal matrix on every iteration; with glibc's default trim threshold
  // the heap top is returned to the kernel each time and re-faulted, which tripled the training time. Keep it.
  static const bool heap_kept = [] { return mallopt(M_TRIM_THRESHOLD, 64 << 20) == 1; }();
  (void)heap_kept;
#endif
  const int n = static_cast<int>(samples.size());
  WAAM_THROW_UNLESS(n >= 2, data.file << ": " << n << " junctions: the network needs at least 2");
  for (int i = 0; i < n; ++i) samples[i].junction.Validate(data.file + ": junction " + samples[i].label);

  const NormalisedSamples d = NormaliseSamples(samples, options.angle_order);
  std::vector<int> sizes = {VoidLengthNetwork::kInputs};
  sizes.insert(sizes.end(), options.hidden.begin(), options.hidden.end());
  sizes.push_back(1);
  const int num_weights = VoidLengthNetwork::NumWeights(sizes);
  const bool bayesian = options.l2 == 0.0 ? false : options.bayesian;
  const Restarts r = RunRestarts(sizes, d, options, bayesian);

  VoidNetworkFit fit;
  fit.usable_restarts = static_cast<int>(r.usable_weights.size());
  if (r.best_weights.empty()) {
    fit.message = "no restart gave a usable solution; last: " + r.last_failure;
    return fit;
  }
  FitInfo info;
  info.fitted = true;
  info.data = data;
  info.solver = r.best.report;
  nlohmann::json training = {{"hidden", options.hidden},
                             {"l2_initial", options.l2},
                             {"l2_final", r.best.l2},
                             {"bayesian", bayesian},
                             {"effective_params", r.best.effective_params},
                             {"num_weights", num_weights},
                             {"restarts", options.restarts},
                             {"seed", options.seed},
                             {"restart_log", r.log}};
  // An ensemble's effective parameter count is taken as the mean over its members.
  const double gamma = options.ensemble ? r.gamma_sum / fit.usable_restarts : r.best.effective_params;
  training["ensemble"] = options.ensemble;
  training["effective_params"] = gamma;
  const std::vector<std::vector<double>> members =
      options.ensemble ? r.usable_weights : std::vector<std::vector<double>>{r.best_weights};
  const VoidLengthNetwork unscored(sizes, members, d.in_min, d.in_max, d.out_min, d.out_max, options.angle_order,
                                   info, training);
  std::vector<double> measured(n), predicted(n);
  for (int i = 0; i < n; ++i) {
    measured[i] = samples[i].void_length_mm;
    predicted[i] = unscored.PredictMm(samples[i].junction);
  }
  // With a penalty the network has fewer effective parameters than weights (gamma); rmse_dof uses gamma.
  info.stats = ComputeFitStats(measured, predicted, num_weights);
  if (n > gamma) info.stats.rmse_dof = std::sqrt(info.stats.sse / (n - gamma));
  fit.model = std::make_unique<VoidLengthNetwork>(sizes, members, d.in_min, d.in_max, d.out_min, d.out_max,
                                                  options.angle_order, info, training);
  fit.ok = true;
  return fit;
}

}  // namespace waam::models
