// Tests of the bead-vs-interpass-temperature model: exactly today's bead at T_ref, volume conservation, the Ceres
// fit recovering known coefficients from a seeded noisy table, the JSON round trip and bad input.
#include "models/bead/bead_temperature_model.h"

#include <cmath>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"

namespace waam::models {
namespace {

using ::testing::HasSubstr;

BeadTemperatureParams Linear() {
  BeadTemperatureParams p;
  p.reference_c = 120.0;
  p.height_per_k = -5e-4;
  p.width_per_k = 4e-4;
  p.min_c = 20.0;
  p.max_c = 500.0;
  return p;
}

TEST(BeadTemperature, FactorsAreExactlyOneAtTheReference) {
  const BeadTemperatureModel linear(Linear());
  EXPECT_EQ(linear.HeightFactor(120.0), 1.0);
  EXPECT_EQ(linear.WidthFactor(120.0), 1.0);
  BeadTemperatureParams v = Linear();
  v.volume_conserving = true;
  const BeadTemperatureModel volume(v);
  EXPECT_EQ(volume.WidthFactor(120.0), 1.0);
  const double h = 1.2345678901234567;
  EXPECT_EQ(h * linear.HeightFactor(120.0), h) << "today's bead, bit for bit";
}

TEST(BeadTemperature, LinearAndVolumeConservingForms) {
  const BeadTemperatureModel linear(Linear());
  EXPECT_NEAR(linear.HeightFactor(320.0), 1.0 - 5e-4 * 200.0, 1e-15);
  EXPECT_NEAR(linear.WidthFactor(320.0), 1.0 + 4e-4 * 200.0, 1e-15);
  EXPECT_EQ(linear.HeightFactor(900.0), linear.HeightFactor(500.0)) << "held at the end of the range";
  BeadTemperatureParams v = Linear();
  v.volume_conserving = true;
  const BeadTemperatureModel volume(v);
  for (double t : {20.0, 200.0, 480.0}) {
    EXPECT_NEAR(volume.HeightFactor(t) * volume.WidthFactor(t), 1.0, 1e-14) << "w h constant at " << t << " degC";
  }
}

BeadTemperatureSamples Synthetic(double h_ref, double k_h, double w_ref, double k_w, double t_ref, bool volume) {
  std::mt19937 rng(33);
  std::normal_distribution<double> noise(0.0, 0.01);
  BeadTemperatureSamples s;
  for (double t = 20.0; t <= 520.0; t += 25.0) {
    const double f = 1.0 + k_h * (t - t_ref);
    s.interpass_c.push_back(t);
    s.height_mm.push_back(h_ref * f + noise(rng));
    s.width_mm.push_back((volume ? w_ref / f : w_ref * (1.0 + k_w * (t - t_ref))) + noise(rng));
  }
  return s;
}

TEST(BeadTemperature, FitRecoversKnownCoefficientsFromANoisyTable) {
  DataSource data;
  data.file = "synthetic.csv";
  const BeadTemperatureFit fit = FitBeadTemperature(Synthetic(1.4, -4e-4, 5.2, 3e-4, 100.0, false), data, 100.0, false);
  ASSERT_TRUE(fit.ok) << fit.message;
  EXPECT_NEAR(fit.model.h_ref_mm(), 1.4, 0.01);
  EXPECT_NEAR(fit.model.w_ref_mm(), 5.2, 0.01);
  EXPECT_NEAR(fit.model.params().height_per_k, -4e-4, 2e-5) << "noise 0.01 mm over 500 K";
  EXPECT_NEAR(fit.model.params().width_per_k, 3e-4, 1e-5);
  EXPECT_LT(fit.model.fit().stats.rmse, 0.015);
  const BeadTemperatureFit vol = FitBeadTemperature(Synthetic(1.4, -4e-4, 5.2, 0.0, 100.0, true), data, 100.0, true);
  ASSERT_TRUE(vol.ok) << vol.message;
  EXPECT_NEAR(vol.model.params().height_per_k, -4e-4, 1e-5) << "both columns inform k_h";
  EXPECT_NEAR(vol.model.w_ref_mm(), 5.2, 0.01);
}

TEST(BeadTemperature, JsonRoundTrip) {
  DataSource data;
  data.file = "synthetic.csv";
  const BeadTemperatureFit fit = FitBeadTemperature(Synthetic(1.4, -4e-4, 5.2, 3e-4, 100.0, false), data, 100.0, false);
  const BeadTemperatureModel back = BeadTemperatureModel::FromJson(fit.model.ToJson(), "x.json");
  EXPECT_EQ(back.params().height_per_k, fit.model.params().height_per_k);
  EXPECT_EQ(back.params().width_per_k, fit.model.params().width_per_k);
  EXPECT_EQ(back.params().reference_c, 100.0);
  EXPECT_EQ(back.HeightFactor(333.0), fit.model.HeightFactor(333.0));
  EXPECT_EQ(back.width_stats().n, fit.model.width_stats().n);
}

TEST(BeadTemperature, BadInputNamesTheProblem) {
  DataSource data;
  data.file = "beads.csv";
  BeadTemperatureSamples three{{20, 100, 200}, {1, 1, 1}, {5, 5, 5}};
  EXPECT_THAT([&] { FitBeadTemperature(three, data, 20.0, false); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("at least 4 rows")));
  BeadTemperatureSamples flat{{100, 100, 100, 100}, {1, 1.1, 1, 1.1}, {5, 5, 5, 5}};
  EXPECT_THAT([&] { FitBeadTemperature(flat, data, 20.0, false); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("2 distinct temperatures")));
  BeadTemperatureSamples negative{{20, 100, 200, 300}, {1, -1, 1, 1}, {5, 5, 5, 5}};
  EXPECT_THAT([&] { FitBeadTemperature(negative, data, 20.0, false); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("row 2")));
  BeadTemperatureParams p = Linear();
  p.height_per_k = -0.01;  // 1 - 0.01 * 380 < 0 at 500 degC
  EXPECT_THAT([&] { BeadTemperatureModel m(p); }, ::testing::ThrowsMessage<InputError>(HasSubstr("must be > 0")));
  p = Linear();
  p.reference_c = 600.0;
  EXPECT_THAT([&] { BeadTemperatureModel m(p); }, ::testing::ThrowsMessage<InputError>(HasSubstr("reference_c")));
}

}  // namespace
}  // namespace waam::models
