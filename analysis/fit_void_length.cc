// `waam fit void-length`: junction samples, network or baseline fit, k-fold / leave-one-out CV, Table 11 hold-out.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "analysis/fit_internal.h"
#include "models/core/error.h"
#include "models/core/progress.h"
#include "models/voids/void_length_baseline.h"
#include "models/voids/void_length_network.h"

namespace waam::analysis::internal {
namespace {
namespace m = waam::models;

m::VoidNetworkOptions NetworkOptions(const FitOptions& options) {
  m::VoidNetworkOptions n;
  n.hidden = options.hidden;
  n.l2 = options.l2;
  n.bayesian = options.bayesian;
  n.restarts = options.restarts;
  n.ensemble = options.ensemble;
  n.seed = options.seed;
  n.angle_order = options.angle_order;
  n.Validate();
  return n;
}

void PrintCv(std::ostream& out, const char* name, const m::CrossValidationResult& cv,
             const m::CrossValidationOptions& o) {
  out << "  " << std::left << std::setw(9) << name << std::right << std::fixed << std::setprecision(3)
      << " MAE " << cv.mae_mm << "  RMSE " << cv.rmse_mm << "  max |err| " << cv.max_abs_mm << " mm  under by > "
      << o.under_tolerance_mm << " mm: " << std::setprecision(1) << 100.0 * cv.share_under << " %";
  if (cv.failed_folds > 0) out << "  (" << cv.failed_folds << " folds failed)";
  out << "\n" << std::defaultfloat;
}

// The model written: trained on every row; fail_message says why it failed (the model is then null).
std::unique_ptr<m::VoidLengthModel> FitWholeData(const FitOptions& options,
                                                 const std::vector<m::JunctionSample>& samples,
                                                 const m::DataSource& source, const m::VoidNetworkOptions& net_options,
                                                 std::string& fail_message) {
  std::unique_ptr<m::VoidLengthModel> model;
  if (options.kind == VoidModelKind::kNetwork) {
    m::VoidNetworkFit fit = m::TrainVoidLengthNetwork(samples, source, net_options);
    if (fit.ok) model = std::move(fit.model);
    fail_message = fit.message;
  } else {
    m::VoidBaselineFit fit = m::FitVoidLengthBaseline(samples, source);
    if (fit.ok) model = std::move(fit.model);
    fail_message = fit.message;
  }
  return model;
}

// The rows whose labels --holdout names, in the order of the labels.
std::vector<int> HeldOutRows(const FitOptions& options, const std::vector<m::JunctionSample>& samples) {
  std::vector<int> held;
  for (const std::string& label : options.holdout) {
    for (int i = 0; i < static_cast<int>(samples.size()); ++i) {
      if (samples[i].label == label) held.push_back(i);
    }
  }
  return held;
}

// The network's shape and training settings, one line.
void PrintNetworkLine(std::ostream& out, int n, const m::VoidNetworkOptions& net_options, int net_params,
                      const FitOptions& options) {
  out << "junction void length L [mm], " << n << " junctions; network " << net_options.hidden.size()
      << " hidden layers (";
  for (std::size_t k = 0; k < net_options.hidden.size(); ++k) out << (k ? "-" : "") << net_options.hidden[k];
  out << "), " << net_params << " weights, " << net_options.restarts << " restarts, l2 " << net_options.l2
      << (net_options.bayesian ? " (Bayesian update)" : "") << (net_options.ensemble ? ", ensemble of restarts" : "")
      << ", angles " << NameOf(options.angle_order) << "\n";
}

// The model written: its parameters, the fit statistics and the solver's summary.
void PrintWrittenModel(std::ostream& out, const m::VoidLengthModel& model, VoidModelKind kind, int net_params) {
  out << "model written: " << model.kind() << "\n";
  if (kind == VoidModelKind::kBaseline) {
    const auto& b = static_cast<const m::VoidLengthBaseline&>(model);
    out << std::setprecision(6) << "  params   : a = " << b.a_mm() << " mm, b = " << b.b_mm()
        << " mm  (L = a + b (1/sin(theta_min/2) - 1))\n";
  } else {
    const nlohmann::json t = model.ToJson()["training"];
    out << "  params   : " << net_params << " weights; l2 after evidence updates " << t["l2_final"].get<double>()
        << ", effective parameters " << std::setprecision(4) << t["effective_params"].get<double>() << "\n";
  }
  const nlohmann::json training = model.ToJson()["training"];
  std::ostringstream note;
  if (!training.is_null()) {
    note << "sqrt(SSE / (n - gamma)), gamma = " << std::setprecision(4)
         << training["effective_params"].get<double>() << " effective parameters";
  }
  PrintStats(out, model.fit().stats, "mm", note.str());
  PrintSolver(out, model.fit().solver);
}

// Dissertation Table 11's hold-out: each held row's measured length and the two models' predictions (null where a
// model failed to train), printed and returned for fit.json.
nlohmann::json PrintHoldout(std::ostream& out, const std::vector<m::JunctionSample>& samples,
                            const std::vector<int>& held, const m::VoidLengthModel* held_net,
                            const m::VoidLengthModel* held_base) {
  nlohmann::json holdout = nlohmann::json::array();
  out << "hold-out (dissertation Table 11), trained on the other "
      << static_cast<int>(samples.size()) - static_cast<int>(held.size())
      << " rows:\n  junction  measured  network  baseline\n";
  for (int i : held) {
    const double pn = held_net ? held_net->PredictMm(samples[i].junction) : NAN;
    const double pb = held_base ? held_base->PredictMm(samples[i].junction) : NAN;
    out << "  " << std::left << std::setw(8) << samples[i].label << std::right << std::fixed << std::setprecision(2)
        << std::setw(10) << samples[i].void_length_mm << std::setw(9) << pn << std::setw(10) << pb << "\n"
        << std::defaultfloat;
    holdout.push_back({{"label", samples[i].label},
                       {"measured_mm", samples[i].void_length_mm},
                       {"network_mm", std::isfinite(pn) ? nlohmann::json(pn) : nlohmann::json(nullptr)},
                       {"baseline_mm", std::isfinite(pb) ? nlohmann::json(pb) : nlohmann::json(nullptr)}});
  }
  return holdout;
}

}  // namespace

std::vector<m::JunctionSample> ReadJunctions(const FitOptions& options, const CsvTable& table) {
  const auto cols = ResolveColumns(options);
  const std::vector<double> eta = table.Numbers(cols.at("eta"));
  std::vector<double> theta[4];
  for (int k = 0; k < 4; ++k) theta[k] = table.Numbers(cols.at("theta" + std::to_string(k + 1)));
  const std::vector<double> void_mm = table.Numbers(cols.at("void"));
  // Labels are optional unless the user named the column explicitly.
  std::vector<std::string> labels;
  const bool label_named = [&] {
    for (const std::string& c : options.columns) {
      if (c.rfind("label=", 0) == 0) return true;
    }
    return false;
  }();
  if (table.HasColumn(cols.at("label")) || label_named) labels = table.Strings(cols.at("label"));

  std::vector<m::JunctionSample> samples(table.rows());
  for (std::size_t i = 0; i < table.rows(); ++i) {
    const std::string place = table.source() + ":" + std::to_string(table.line(i));
    WAAM_THROW_UNLESS(eta[i] >= 1.0 && eta[i] == std::floor(eta[i]),
                      place << ": column '" << cols.at("eta") << "': " << eta[i] << " is not a whole number >= 1");
    samples[i].junction.turning_points = static_cast<int>(eta[i]);
    for (int k = 0; k < 4; ++k) samples[i].junction.angles_deg[k] = theta[k][i];
    samples[i].junction.Validate(place);
    WAAM_THROW_UNLESS(void_mm[i] >= 0.0,
                      place << ": column '" << cols.at("void") << "': " << void_mm[i] << " mm must be >= 0");
    samples[i].void_length_mm = void_mm[i];
    samples[i].label = labels.empty() ? "row " + std::to_string(table.line(i)) : labels[i];
  }
  return samples;
}

FitOutcome RunVoidLength(const FitOptions& options, const CsvTable& table, std::ostream& out) {
  const m::VoidNetworkOptions net_options = NetworkOptions(options);
  const std::vector<m::JunctionSample> samples = ReadJunctions(options, table);
  const m::DataSource source = MakeSource(options, table, ResolveColumns(options));
  const int n = static_cast<int>(samples.size());
  const int net_params = m::VoidLengthNetwork::NumWeights([&] {
    std::vector<int> sizes = {5};
    sizes.insert(sizes.end(), options.hidden.begin(), options.hidden.end());
    sizes.push_back(1);
    return sizes;
  }());
  WAAM_THROW_UNLESS(n >= 3, source.file << ": " << n << " junctions: need at least 3 to fit and validate");

  m::CrossValidationOptions cv_options;
  cv_options.folds = options.folds;
  cv_options.leave_one_out = options.leave_one_out;
  cv_options.seed = options.seed;
  const int folds = options.leave_one_out ? n : options.folds;
  WAAM_THROW_UNLESS(folds >= 2 && folds <= n, "--folds " << folds << ": must be between 2 and the " << n
                                                         << " junctions");

  const m::VoidLengthTrainer train_network = [&](const std::vector<m::JunctionSample>& training) {
    m::VoidNetworkFit fit = m::TrainVoidLengthNetwork(training, source, net_options);
    return std::unique_ptr<m::VoidLengthModel>(fit.ok ? std::move(fit.model) : nullptr);
  };
  const m::VoidLengthTrainer train_baseline = [&](const std::vector<m::JunctionSample>& training) {
    m::VoidBaselineFit fit = m::FitVoidLengthBaseline(training, source);
    return std::unique_ptr<m::VoidLengthModel>(fit.ok ? std::move(fit.model) : nullptr);
  };

  // Progress over network trainings: the final fit, the folds and the hold-out fit.
  Progress progress("fit void-length", static_cast<std::size_t>(folds + 2), "trainings", options.quiet);
  std::size_t done = 0;

  std::string fail_message;
  const std::unique_ptr<m::VoidLengthModel> model = FitWholeData(options, samples, source, net_options, fail_message);
  progress.Update(++done);

  const m::CrossValidationResult cv_net =
      m::CrossValidate(samples, train_network, cv_options, [&](int, int) { progress.Update(++done); });
  const m::CrossValidationResult cv_base = m::CrossValidate(samples, train_baseline, cv_options);

  // Dissertation Table 11: train on the other rows, predict the named junctions.
  const std::vector<int> held = HeldOutRows(options, samples);
  std::unique_ptr<m::VoidLengthModel> held_net, held_base;
  if (!held.empty()) {
    std::vector<m::JunctionSample> rest;
    for (int i = 0; i < n; ++i) {
      if (std::find(held.begin(), held.end(), i) == held.end()) rest.push_back(samples[i]);
    }
    held_net = train_network(rest);
    held_base = train_baseline(rest);
  }
  progress.Update(++done);
  progress.Finish();

  PrintNetworkLine(out, n, net_options, net_params, options);
  if (model) PrintWrittenModel(out, *model, options.kind, net_params);
  out << (options.leave_one_out ? "leave-one-out" : std::to_string(folds) + "-fold") << " cross-validation (seed "
      << options.seed << "), held-out error = predicted - measured:\n";
  PrintCv(out, "network", cv_net, cv_options);
  PrintCv(out, "baseline", cv_base, cv_options);
  nlohmann::json holdout = nlohmann::json::array();
  if (!held.empty()) {
    holdout = PrintHoldout(out, samples, held, held_net.get(), held_base.get());
  } else if (!options.holdout.empty()) {
    out << "hold-out: none of the labels were found in the data; skipped\n";
  }
  if (!model) return Finish(false, fail_message, nullptr, options, out);
  nlohmann::json j = model->ToJson();
  j["cross_validation"] = {{"network", ToJson(cv_net, cv_options)}, {"baseline", ToJson(cv_base, cv_options)}};
  j["holdout"] = holdout;
  return Finish(true, "", j, options, out);
}

}  // namespace waam::analysis::internal
