// Tests of the junction void-length models: baseline and network fits, JSON, cross-validation invariants.
#include <cmath>
#include <numeric>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/csv.h"
#include "models/core/error.h"
#include "models/core/numbers.h"
#include "models/voids/void_length_baseline.h"
#include "models/voids/void_length_network.h"
#include "test_util.h"

namespace waam::models {
namespace {
using ::testing::HasSubstr;

DataSource VoidSource(const std::string& file) { return DataSource{file, {}, {}, 0, ""}; }

// The 63 junction geometries of Appendix A1 with their measured void lengths.
std::vector<JunctionSample> AppendixA1() {
  const CsvTable t = CsvTable::Read(waam::testing::ModelsData("nguyen2022_appendixA1_junction_voids.csv"));
  const auto eta = t.Numbers("eta"), l = t.Numbers("void_length_mm");
  const auto t1 = t.Numbers("theta1_deg"), t2 = t.Numbers("theta2_deg"), t3 = t.Numbers("theta3_deg"),
             t4 = t.Numbers("theta4_deg");
  const auto group = t.Strings("group");
  std::vector<JunctionSample> out;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    out.push_back({Junction{static_cast<int>(eta[i]), {t1[i], t2[i], t3[i], t4[i]}}, l[i], group[i]});
  }
  return out;
}

// The same geometries with a smooth synthetic void length.
std::vector<JunctionSample> Synthetic(double a, double b) {
  std::vector<JunctionSample> s = AppendixA1();
  for (JunctionSample& j : s) j.void_length_mm = a + b * SharpnessTerm(j.junction);
  return s;
}

TEST(VoidLengthBaselineTest, FitRecoversKnownParameters) {
  const VoidBaselineFit fit = FitVoidLengthBaseline(Synthetic(1.5, 3.0), VoidSource("synthetic"));
  ASSERT_TRUE(fit.ok) << fit.message;
  EXPECT_NEAR(fit.model->a_mm(), 1.5, 1e-8);
  EXPECT_NEAR(fit.model->b_mm(), 3.0, 1e-8);
}

TEST(VoidLengthBaselineTest, SharpnessTermFollowsEquation43) {
  const Junction straight{2, {180, 90, 90, 0}};
  EXPECT_NEAR(SharpnessTerm(straight), 1.0 / std::sin(kPi / 4) - 1.0, 1e-12) << "theta_min = 90 deg";
  const Junction sharp{4, {165, 15, 165, 15}};
  EXPECT_NEAR(SharpnessTerm(sharp), 1.0 / std::sin(7.5 * kPi / 180) - 1.0, 1e-12);
}

VoidNetworkOptions SmallNetwork() {
  VoidNetworkOptions o;
  o.hidden = {5};
  o.restarts = 2;
  o.max_iterations = 100;
  return o;
}

TEST(VoidLengthNetworkTest, LearnsASmoothSyntheticFunction) {
  const std::vector<JunctionSample> data = Synthetic(1.0, 2.0);
  const VoidNetworkFit fit = TrainVoidLengthNetwork(data, VoidSource("synthetic"), SmallNetwork());
  ASSERT_TRUE(fit.ok) << fit.message;
  EXPECT_GT(fit.model->fit().stats.r2, 0.97) << "a 5-neuron network should fit L = 1 + 2 (1/sin(theta_min/2) - 1)";
  EXPECT_EQ(fit.usable_restarts, 2);
}

TEST(VoidLengthNetworkTest, TrainingIsDeterministicForASeed) {
  const std::vector<JunctionSample> data = AppendixA1();
  const VoidNetworkFit a = TrainVoidLengthNetwork(data, VoidSource("a1"), SmallNetwork());
  const VoidNetworkFit b = TrainVoidLengthNetwork(data, VoidSource("a1"), SmallNetwork());
  ASSERT_TRUE(a.ok && b.ok);
  EXPECT_EQ(a.model->ToJson()["params"]["members"], b.model->ToJson()["params"]["members"]);
}

TEST(VoidLengthModelTest, BothKindsRoundTripThroughFiles) {
  const auto dir = waam::testing::TestDir();
  const std::vector<JunctionSample> data = AppendixA1();
  const VoidNetworkFit net = TrainVoidLengthNetwork(data, VoidSource("a1"), SmallNetwork());
  const VoidBaselineFit base = FitVoidLengthBaseline(data, VoidSource("a1"));
  ASSERT_TRUE(net.ok && base.ok);
  const std::vector<const VoidLengthModel*> models = {net.model.get(), base.model.get()};
  for (const VoidLengthModel* m : models) {
    const auto path = waam::testing::WriteText(dir, m->kind() + ".json", m->ToJson().dump());
    const std::unique_ptr<VoidLengthModel> back = LoadVoidLengthModel(path);
    EXPECT_EQ(back->kind(), m->kind());
    for (const JunctionSample& s : data) EXPECT_DOUBLE_EQ(back->PredictMm(s.junction), m->PredictMm(s.junction));
    EXPECT_EQ(back->fit().stats.n, 63u);
  }
  nlohmann::json broken = net.model->ToJson();
  broken["params"]["members"][0].erase(0);
  const auto path = waam::testing::WriteText(dir, "broken.json", broken.dump());
  try {
    LoadVoidLengthModel(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("broken.json: /params/members/0 has"));
  }
}

TEST(VoidLengthNetworkTest, EnsemblePredictsTheMeanOfItsMembers) {
  const std::vector<JunctionSample> data = AppendixA1();
  VoidNetworkOptions o = SmallNetwork();
  o.ensemble = true;
  const VoidNetworkFit fit = TrainVoidLengthNetwork(data, VoidSource("a1"), o);
  ASSERT_TRUE(fit.ok) << fit.message;
  const nlohmann::json j = fit.model->ToJson();
  ASSERT_EQ(j["params"]["members"].size(), 2u);
  std::vector<VoidLengthNetwork> single;
  for (int k = 0; k < 2; ++k) {
    nlohmann::json one = j;
    one["params"]["members"] = nlohmann::json::array({j["params"]["members"][k]});
    single.push_back(VoidLengthNetwork::FromJson(one, "member"));
  }
  for (const JunctionSample& s : data) {
    const double mean = 0.5 * (single[0].PredictMm(s.junction) + single[1].PredictMm(s.junction));
    EXPECT_NEAR(fit.model->PredictMm(s.junction), mean, 1e-12) << s.label;
  }
}

TEST(VoidLengthNetworkTest, SortingTheAnglesMergesDifferentJunctions) {
  // F1 (108/72/108/72, L 4.6 mm) and F9 (108/72/72/108, L 3.1 mm) differ only in the order round the junction.
  const Junction f1{4, {108, 72, 108, 72}}, f9{4, {108, 72, 72, 108}};
  EXPECT_NE(NetworkInputs(f1, AngleOrder::kAsGiven), NetworkInputs(f9, AngleOrder::kAsGiven));
  EXPECT_EQ(NetworkInputs(f1, AngleOrder::kSortedDescending), NetworkInputs(f9, AngleOrder::kSortedDescending));
}

// A trainer whose model predicts the mean of its training targets: its cross-validation is known in closed form.
std::unique_ptr<VoidLengthModel> MeanTrainer(const std::vector<JunctionSample>& training) {
  double sum = 0.0;
  for (const JunctionSample& s : training) sum += s.void_length_mm;
  return std::make_unique<VoidLengthBaseline>(sum / training.size(), 0.0);
}

TEST(CrossValidationTest, LeaveOneOutOfTheMeanMatchesTheClosedForm) {
  const std::vector<JunctionSample> data = AppendixA1();
  CrossValidationOptions o;
  o.leave_one_out = true;
  const CrossValidationResult cv = CrossValidate(data, MeanTrainer, o);
  EXPECT_EQ(cv.folds, 63);
  const double n = data.size();
  double total = 0.0;
  for (const JunctionSample& s : data) total += s.void_length_mm;
  double abs_sum = 0.0, max_abs = 0.0;
  int under = 0;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const double prediction = (total - data[i].void_length_mm) / (n - 1);
    EXPECT_NEAR(cv.predicted_mm[i], prediction, 1e-12);
    const double err = prediction - data[i].void_length_mm;
    abs_sum += std::abs(err);
    max_abs = std::max(max_abs, std::abs(err));
    under += err < -1.3;
  }
  EXPECT_NEAR(cv.mae_mm, abs_sum / n, 1e-12);
  EXPECT_NEAR(cv.max_abs_mm, max_abs, 1e-12);
  EXPECT_NEAR(cv.share_under, under / n, 1e-12);
}

TEST(CrossValidationTest, FoldsAreSeededAndEveryRowIsHeldOutOnce) {
  const std::vector<JunctionSample> data = AppendixA1();
  CrossValidationOptions o;
  o.folds = 5;
  o.seed = 7;
  const auto trainer = [&](const std::vector<JunctionSample>& t) {
    return std::unique_ptr<VoidLengthModel>(FitVoidLengthBaseline(t, VoidSource("a1")).model.release());
  };
  const CrossValidationResult a = CrossValidate(data, trainer, o), b = CrossValidate(data, trainer, o);
  EXPECT_EQ(a.predicted_mm, b.predicted_mm) << "same seed, same folds";
  for (double p : a.predicted_mm) EXPECT_TRUE(std::isfinite(p)) << "every row must get a held-out prediction";
  o.seed = 8;
  EXPECT_NE(CrossValidate(data, trainer, o).predicted_mm, a.predicted_mm) << "another seed, other folds";
}

TEST(CrossValidationTest, BadFoldCountsAreNamed) {
  const std::vector<JunctionSample> data = AppendixA1();
  CrossValidationOptions o;
  o.folds = 64;
  try {
    CrossValidate(data, MeanTrainer, o);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("64 folds for 63 junctions"));
  }
}

TEST(VoidLengthModelTest, BadJunctionsAndOptionsAreNamed) {
  try {
    Junction{3, {180, 90, 0, 0}}.Validate("data.csv:5");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("data.csv:5: only 2 angles > 0"));
  }
  VoidNetworkOptions o;
  o.hidden = {0};
  try {
    o.Validate();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("hidden layer of 0 neurons"));
  }
}

}  // namespace
}  // namespace waam::models
