// Tests of the bead models: parabolic section, volume balance, CSW, speed-height and width-height fits and inverses.
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/Dense>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/bead/csw_model.h"
#include "models/bead/parabolic_bead.h"
#include "models/bead/speed_height_model.h"
#include "models/bead/width_height_model.h"
#include "models/core/csv.h"
#include "models/core/error.h"
#include "test_util.h"

namespace waam::models {
namespace {
using ::testing::HasSubstr;
constexpr double kInf = std::numeric_limits<double>::infinity();

DataSource Source(const std::string& file) { return DataSource{file, {}, {}, 0, ""}; }

TEST(ParabolicBeadTest, AreaIsTheIntegralOfTheProfile) {
  const ParabolicBead bead{5.3, 1.8};
  const int steps = 20000;
  double integral = 0.0;
  const double dy = bead.width_mm / steps;
  for (int i = 0; i < steps; ++i) integral += bead.ProfileZ(-0.5 * bead.width_mm + (i + 0.5) * dy) * dy;
  EXPECT_NEAR(integral, bead.Area(), 1e-6) << "eq. 3.3: A = 2wh/3 must equal the integral of eq. 3.2";
  EXPECT_DOUBLE_EQ(bead.ProfileZ(0.0), 1.8);
  EXPECT_DOUBLE_EQ(bead.ProfileZ(2.65), 0.0);
  EXPECT_DOUBLE_EQ(bead.ProfileZ(10.0), 0.0);
}

TEST(ParabolicBeadTest, VolumeBalanceAndItsInversesAgree) {
  // Eq. 3.4: 2wh/3 * v_t = pi d^2 / 4 * v_w.
  const double d = 1.0, vw = 3200.0, vt = 500.0, h = 1.2;
  const double w = WidthFromVolumeBalance(h, d, vw, vt);
  EXPECT_NEAR(w, 3.0 * std::numbers::pi * vw * d * d / (8.0 * h * vt), 1e-12);
  const ParabolicBead bead{w, h};
  EXPECT_NEAR(bead.Area() * vt, WireArea(d) * vw, 1e-9) << "bead volume rate must equal wire volume rate";
  EXPECT_NEAR(TravelSpeedForArea(bead.Area(), d, vw), vt, 1e-9);
  EXPECT_NEAR(ImpliedEfficiency(ParabolicBead{w, h}, d, vw, vt), 1.0, 1e-12);
  EXPECT_NEAR(BeadAreaFromWireFeed(d, vw, vt, 0.8), 0.8 * bead.Area(), 1e-12);
}

TEST(ParabolicBeadTest, BadValuesAreNamed) {
  EXPECT_THROW(WireArea(0.0), InputError);
  try {
    BeadAreaFromWireFeed(1.0, 3200, 500, 1.5);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("efficiency = 1.5: must be in (0, 1]"));
  }
}

CswSamples SyntheticCsw(const CswParams& p, double noise, unsigned seed) {
  CswSamples s;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> e(0.0, noise);
  for (double r : {30.0, 60.0, 120.0, kInf}) {
    for (double v : {250.0, 400.0, 600.0, 900.0}) {
      s.speed_mm_per_min.push_back(v);
      s.radius_mm.push_back(r);
      s.width_mm.push_back(p.m / std::cbrt(v) + p.p / r + p.t + e(rng));
    }
  }
  return s;
}

TEST(CswModelTest, FitRecoversKnownParameters) {
  const CswParams truth{80.0, 40.0, -1.5};
  const CswFit fit = FitCsw(SyntheticCsw(truth, 0.0, 1), Source("synthetic"));
  ASSERT_TRUE(fit.ok) << fit.message;
  EXPECT_NEAR(fit.model.params().m, truth.m, 1e-6);
  EXPECT_NEAR(fit.model.params().p, truth.p, 1e-6);
  EXPECT_NEAR(fit.model.params().t, truth.t, 1e-6);
  EXPECT_NEAR(fit.model.fit().stats.r2, 1.0, 1e-12);
}

CswSamples DaiTable1() {
  const CsvTable t = CsvTable::Read(waam::testing::ModelsData("dai2020_csw_table1.csv"));
  return {t.Numbers("travel_speed_mm_per_min"), t.Numbers("curvature_radius_mm"), t.Numbers("width_mm")};
}

TEST(CswModelTest, TableOneFitReproducesThePublishedGoodnessOfFit) {
  const CswFit fit = FitCsw(DaiTable1(), Source("dai2020_csw_table1.csv"));
  ASSERT_TRUE(fit.ok) << fit.message;
  // Dai et al.: "confidence coefficient 98.02 %" = R^2, "RMSE 0.2777 mm" = sqrt(SSE / (n - 3)) (12 beads, 3 params).
  EXPECT_NEAR(fit.model.fit().stats.r2, 0.9802, 5e-5);
  // Our fit gives 0.27746; the paper prints 0.2777 (0.1 % apart, see the note in the report).
  EXPECT_NEAR(fit.model.fit().stats.rmse_dof, 0.2777, 5e-4);
  EXPECT_EQ(fit.model.fit().stats.n, 12u);
}

TEST(CswModelTest, CeresAgreesWithEigenLeastSquares) {
  const CswSamples s = DaiTable1();
  Eigen::MatrixXd a(12, 3);
  Eigen::VectorXd w(12);
  for (int i = 0; i < 12; ++i) {
    a.row(i) << 1.0 / std::cbrt(s.speed_mm_per_min[i]), 1.0 / s.radius_mm[i], 1.0;
    w[i] = s.width_mm[i];
  }
  const Eigen::Vector3d x = a.colPivHouseholderQr().solve(w);
  const CswFit fit = FitCsw(s, Source("t"));
  EXPECT_NEAR(fit.model.params().m, x[0], 1e-6);
  EXPECT_NEAR(fit.model.params().p, x[1], 1e-6);
  EXPECT_NEAR(fit.model.params().t, x[2], 1e-6);
}

TEST(CswModelTest, SpeedForWidthInvertsWidthAndReportsClamps) {
  const CswModel model(CswParams{85.55, 52.74, -1.754}, SpeedRange{300.0, 900.0});
  for (double r : {30.0, 90.0, kInf}) {
    for (double v : {300.0, 450.0, 900.0}) {
      const SpeedChoice c = model.SpeedForWidth(model.Width(v, r), r);
      EXPECT_NEAR(c.speed_mm_per_min, v, 1e-6 * v) << "r = " << r;
      EXPECT_EQ(c.clamp, SpeedClamp::kNone);
    }
  }
  const SpeedChoice too_narrow = model.SpeedForWidth(5.0, 90.0);
  EXPECT_EQ(too_narrow.clamp, SpeedClamp::kAtMaximum);
  EXPECT_DOUBLE_EQ(too_narrow.speed_mm_per_min, 900.0);
  EXPECT_GT(too_narrow.achieved_mm, 5.0) << "the clamped speed gives a wider bead than asked";
  const SpeedChoice too_wide = model.SpeedForWidth(14.0, 30.0);
  EXPECT_EQ(too_wide.clamp, SpeedClamp::kAtMinimum);
  EXPECT_LT(too_wide.achieved_mm, 14.0);
  EXPECT_EQ(model.SpeedForWidth(1.0, INFINITY).clamp, SpeedClamp::kAtMaximum) << "w below t: unreachable";
}

TEST(CswModelTest, JsonRoundTrips) {
  const CswFit fit = FitCsw(DaiTable1(), Source("dai.csv"));
  const CswModel back = CswModel::FromJson(nlohmann::json::parse(fit.model.ToJson().dump()), "mem");
  EXPECT_EQ(back.params().m, fit.model.params().m);
  EXPECT_EQ(back.params().t, fit.model.params().t);
  EXPECT_EQ(back.feasible().max_mm_per_min, 900.0);
  EXPECT_EQ(back.fit().stats.r2, fit.model.fit().stats.r2);
  EXPECT_EQ(back.fit().data.file, "dai.csv");
  EXPECT_EQ(back.ToJson(), fit.model.ToJson());
}

TEST(CswModelTest, TooFewRowsAndBadJsonAreNamed) {
  CswSamples s = DaiTable1();
  s.speed_mm_per_min.resize(3), s.radius_mm.resize(3), s.width_mm.resize(3);
  try {
    FitCsw(s, Source("short.csv"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("short.csv: 3 rows: the CSW model has 3 parameters and needs at least 4 rows"));
  }
  nlohmann::json j = FitCsw(DaiTable1(), Source("t")).model.ToJson();
  j["params"].erase("p");
  try {
    CswModel::FromJson(j, "csw.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("csw.json: /params/p is missing or not a number"));
  }
}

// Table 18 rows in the feasible window 150-900 mm/min (row 1 at 100 mm/min gave a wavy wall), row 6 at 350.
void Table18(std::vector<double>* v, std::vector<double>* h, std::vector<double>* w) {
  const CsvTable t = CsvTable::Read(waam::testing::ModelsData("nguyen2022_table18_bead_vs_speed.csv"));
  const auto speed = t.Numbers("travel_speed_mm_per_min"), height = t.Numbers("height_mm"), width = t.Numbers("width_mm");
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (speed[i] < 150.0) continue;
    v->push_back(speed[i]), h->push_back(height[i]), w->push_back(width[i]);
  }
}

TEST(SpeedHeightModelTest, FitRecoversKnownParametersInBothSpaces) {
  SpeedHeightSamples s;
  for (double h = 0.9; h < 2.8; h += 0.1) {
    s.height_mm.push_back(h);
    s.speed_mm_per_min.push_back(700.0 * std::pow(h, -2.1));
  }
  for (PowerLawSpace space : {PowerLawSpace::kLinear, PowerLawSpace::kLog}) {
    const SpeedHeightFit fit = FitSpeedHeight(s, Source("synthetic"), space);
    ASSERT_TRUE(fit.ok) << fit.message;
    EXPECT_NEAR(fit.model.params().a, 700.0, 1e-6);
    EXPECT_NEAR(fit.model.params().b, -2.1, 1e-9);
  }
}

TEST(SpeedHeightModelTest, TableEighteenLogFitReproducesThePublishedR2) {
  SpeedHeightSamples s;
  std::vector<double> w;
  Table18(&s.speed_mm_per_min, &s.height_mm, &w);
  ASSERT_EQ(s.height_mm.size(), 16u);
  const SpeedHeightFit fit = FitSpeedHeight(s, Source("t18"), PowerLawSpace::kLog);
  ASSERT_TRUE(fit.ok) << fit.message;
  // Dissertation eq. 6.6: R^2 = 0.9923, which is the R^2 of ln v of the log-log line.
  EXPECT_NEAR(fit.model.log_stats().r2, 0.9923, 1e-4);
  EXPECT_NEAR(fit.model.params().b, -2.069, 0.03);
}

TEST(SpeedHeightModelTest, InverseAndClamp) {
  const SpeedHeightModel model(SpeedHeightParams{686.4, -2.069}, SpeedRange{150.0, 900.0});
  for (double h : {1.0, 1.5, 2.0}) EXPECT_NEAR(model.Height(model.Speed(h)), h, 1e-12);
  const SpeedChoice in = model.SpeedForHeight(1.5);
  EXPECT_EQ(in.clamp, SpeedClamp::kNone);
  EXPECT_NEAR(in.achieved_mm, 1.5, 1e-12);
  const SpeedChoice thin = model.SpeedForHeight(0.5);
  EXPECT_EQ(thin.clamp, SpeedClamp::kAtMaximum);
  EXPECT_GT(thin.achieved_mm, 0.5) << "at 900 mm/min the layer is thicker than 0.5 mm";
  EXPECT_EQ(model.SpeedForHeight(3.0).clamp, SpeedClamp::kAtMinimum);
  const SpeedHeightModel back = SpeedHeightModel::FromJson(model.ToJson(), "mem");
  EXPECT_EQ(back.params().a, 686.4);
  EXPECT_EQ(back.feasible().min_mm_per_min, 150.0);
}

TEST(WidthHeightModelTest, FitRecoversKnownPolynomials) {
  const std::vector<double> truth = {4.3, -11.8, 18.1, -8.87, 1.51};
  WidthHeightSamples s;
  for (double h = 0.9; h < 2.75; h += 0.1) {
    double w = 0.0;
    for (int k = 4; k >= 0; --k) w = w * h + truth[k];
    s.height_mm.push_back(h), s.width_mm.push_back(w);
  }
  const WidthHeightFit fit = FitWidthHeight(s, Source("synthetic"), 4);
  ASSERT_TRUE(fit.ok) << fit.message;
  for (int k = 0; k <= 4; ++k) EXPECT_NEAR(fit.model.coefficients()[k], truth[k], 1e-5) << "c" << k;
}

TEST(WidthHeightModelTest, TableEighteenReproducesThePublishedFit) {
  WidthHeightSamples s;
  std::vector<double> v;
  Table18(&v, &s.height_mm, &s.width_mm);
  const WidthHeightFit fit = FitWidthHeight(s, Source("t18"), 4);
  ASSERT_TRUE(fit.ok) << fit.message;
  EXPECT_NEAR(fit.model.fit().stats.r2, 0.9886, 1e-4) << "dissertation eq. 6.7";
  // Printed eq. 6.7 coefficients (ascending powers); the fit of rows 2-17 lands within 1 % of each.
  const std::vector<double> printed = {4.3077, -11.823, 18.132, -8.8702, 1.5093};
  for (int k = 0; k <= 4; ++k) EXPECT_NEAR(fit.model.coefficients()[k], printed[k], 0.01 * std::abs(printed[k]));
  // Cross-check against Eigen on the Vandermonde system.
  Eigen::MatrixXd a(s.height_mm.size(), 5);
  Eigen::VectorXd w(s.height_mm.size());
  for (std::size_t i = 0; i < s.height_mm.size(); ++i) {
    for (int k = 0; k <= 4; ++k) a(i, k) = std::pow(s.height_mm[i], k);
    w[i] = s.width_mm[i];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(w);
  for (int k = 0; k <= 4; ++k) EXPECT_NEAR(fit.model.coefficients()[k], c[k], 1e-5 * std::abs(c[k]));
}

TEST(WidthHeightModelTest, SetpointCombinesBothModelsAndRoundTrips) {
  const SpeedHeightModel sh(SpeedHeightParams{686.4, -2.069}, SpeedRange{150.0, 900.0});
  const WidthHeightModel wh({4.3077, -11.823, 18.132, -8.8702, 1.5093}, 0.882, 2.102);
  const BeadSetpoint sp = SetpointForHeight(sh, wh, 1.49);
  EXPECT_NEAR(sp.speed.achieved_mm, 1.49, 1e-12);
  // Dissertation Table 19: h = 1.49 mm -> predicted w = 5.04 mm.
  EXPECT_NEAR(sp.width_mm, 5.04, 0.01);
  EXPECT_TRUE(sp.width_in_range);
  const WidthHeightModel back = WidthHeightModel::FromJson(wh.ToJson(), "mem");
  EXPECT_EQ(back.coefficients(), wh.coefficients());
  EXPECT_FALSE(back.InRange(2.5));
}

TEST(WidthHeightModelTest, FewerRowsThanParametersIsAnError) {
  WidthHeightSamples s{{1.0, 1.2, 1.4, 1.6, 1.8}, {3, 4, 5, 6, 7}};
  try {
    FitWidthHeight(s, Source("five.csv"), 4);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("five.csv: 5 rows: a degree-4 polynomial has 5 parameters and needs at least 6"));
  }
}

}  // namespace
}  // namespace waam::models
