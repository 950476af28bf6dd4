// A physically motivated void-length baseline: L = a + b (1/sin(theta_min/2) - 1) (shape of eq. 4.3/4.6).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/voids/void_length_model.h"

namespace waam::models {

// Eq. 4.3 says the material missing at a turning point grows with 1/sin(theta/2) - 1 of its smallest angle; the
// baseline regresses the measured void length on that term: L = a + b * (1/sin(theta_min/2) - 1), a and b in mm.
class VoidLengthBaseline : public VoidLengthModel {
 public:
  VoidLengthBaseline(double a_mm, double b_mm, FitInfo fit = {});

  double PredictMm(const Junction& junction) const override;
  std::string kind() const override { return "baseline"; }
  nlohmann::json ToJson() const override;
  const FitInfo& fit() const override { return fit_; }
  static VoidLengthBaseline FromJson(const nlohmann::json& j, const std::string& where);

  double a_mm() const { return a_mm_; }
  double b_mm() const { return b_mm_; }

 private:
  double a_mm_;
  double b_mm_;
  FitInfo fit_;
};

// The regressor 1/sin(theta_min/2) - 1 of a junction (0 for a straight pass, grows without bound as theta -> 0).
double SharpnessTerm(const Junction& junction);

struct VoidBaselineFit {
  std::unique_ptr<VoidLengthBaseline> model;
  bool ok = false;
  std::string message;
};

// Least-squares fit of (a, b) with Ceres. Throws InputError (naming `data.file`) for fewer than 3 samples.
VoidBaselineFit FitVoidLengthBaseline(const std::vector<JunctionSample>& samples, const DataSource& data);

}  // namespace waam::models
