// A small feed-forward network for junction void length (dissertation eq. 4.7, Fig. 33), trained with Ceres.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/core/enum_names.h"
#include "models/voids/void_length_model.h"

namespace waam::models {

// How the four angles enter the network. The dissertation states "descending order" but prints them in the order
// met going round the junction from the largest (F1 108/72/108/72 and F9 108/72/72/108 are different junctions
// with different voids); sorting merges such pairs into identical inputs with different targets.
// Its name is the model file's /params/angle_order and `waam fit void-length --angle-order`.
enum class AngleOrder { kAsGiven, kSortedDescending };
constexpr std::array<EnumName<AngleOrder>, 2> EnumNames(AngleOrder) {
  return {{{AngleOrder::kAsGiven, "as_given"}, {AngleOrder::kSortedDescending, "sorted_descending"}}};
}
WAAM_ENUM_JSON(AngleOrder)

struct VoidNetworkOptions {
  std::vector<int> hidden = {7, 7};  // neurons per hidden layer (tanh); the dissertation: two layers of 7
  double l2 = 0.01;                  // weight of sum(w^2) against the sum of squared normalised residuals
  bool bayesian = true;              // re-estimate l2 from the evidence (MacKay), like MATLAB's trainbr
  int restarts = 5;                  // seeded random initialisations
  bool ensemble = true;              // average every usable restart (else keep the lowest training objective)
  unsigned long long seed = 1;
  int max_iterations = 200;
  AngleOrder angle_order = AngleOrder::kAsGiven;
  // Throws InputError naming the option if a value is out of range.
  void Validate() const;
};

// Inputs (eta, theta1..theta4) and output are mapped linearly to [-1, 1] with the training data's min/max
// (MATLAB mapminmax); hidden layers use tanh, the output layer is linear. With several members (an ensemble of
// restarts) the prediction is their mean.
class VoidLengthNetwork : public VoidLengthModel {
 public:
  static constexpr int kInputs = 5;

  VoidLengthNetwork(std::vector<int> layer_sizes, std::vector<std::vector<double>> members, std::vector<double> input_min,
                    std::vector<double> input_max, double output_min, double output_max, AngleOrder order,
                    FitInfo fit = {}, nlohmann::json training = nullptr);

  double PredictMm(const Junction& junction) const override;
  std::string kind() const override { return "network"; }
  nlohmann::json ToJson() const override;
  const FitInfo& fit() const override { return fit_; }
  static VoidLengthNetwork FromJson(const nlohmann::json& j, const std::string& where);

  // Number of weights and biases of a network with these layer sizes (inputs, hidden..., 1).
  static int NumWeights(const std::vector<int>& layer_sizes);
  const std::vector<int>& layer_sizes() const { return layer_sizes_; }

 private:
  std::vector<int> layer_sizes_;
  std::vector<std::vector<double>> members_;  // weights of each member network
  std::vector<double> input_min_, input_max_;
  double output_min_, output_max_;
  AngleOrder order_;
  FitInfo fit_;
  nlohmann::json training_;  // options and restart record, kept in the file
};

// The network's five inputs for a junction, in the chosen angle order.
std::vector<double> NetworkInputs(const Junction& junction, AngleOrder order);

struct VoidNetworkFit {
  std::unique_ptr<VoidLengthNetwork> model;  // all usable restarts, or the best one (null if every restart failed)
  bool ok = false;
  std::string message;          // why it failed, when !ok
  int usable_restarts = 0;
};

// Trains the network on `samples` with `options.restarts` seeded restarts. Throws InputError (naming `data.file`)
// for fewer samples than 2, invalid junctions or options.
VoidNetworkFit TrainVoidLengthNetwork(const std::vector<JunctionSample>& samples, const DataSource& data,
                                      const VoidNetworkOptions& options);

}  // namespace waam::models
