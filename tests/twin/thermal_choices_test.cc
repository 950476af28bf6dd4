// A run that follows another's solver choices (ThermalSimulation::RecordChoices / FollowChoices): the same run
// again bit for bit, and a continuous response to the heat and the losses, which a fit differences.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "models/core/error.h"
#include "tests/twin/thermal_test_util.h"

namespace waam::twin {
namespace {

const std::vector<Eigen::Vector3d> kChoiceProbes = {{0, 10, -1}, {10, 0, -3}, {0, 0, 5}, {-16, 0, 3}};

// Three layers in welds of 10 mm at `heat_w`, the probes recorded after each weld and each second of cooling (the
// records ending no batch); returns every record's probes in order.
std::vector<double> ChoiceBuild(ThermalSimulation& sim, double heat_w, int layers = 3) {
  for (const Eigen::Vector3d& p : kChoiceProbes) sim.AddProbe(p);
  std::vector<std::size_t> ids;
  for (int layer = 0; layer < layers; ++layer) {
    const double z = 2.0 * (layer + 1);
    const double x0 = layer % 2 == 0 ? -20.0 : 20.0;
    const double dir = x0 < 0 ? 10.0 : -10.0;
    for (int piece = 0; piece < 4; ++piece) {
      const double a = x0 + dir * piece;
      sim.Weld(Eigen::Vector3d(a, 0, z), Eigen::Vector3d(a + dir, 0, z), 4.0, 2.0, heat_w, 1.25);
      ids.push_back(sim.RecordProbes());
    }
    for (int second = 0; second < 4; ++second) {
      sim.Cool(1.0);
      ids.push_back(sim.RecordProbes());
    }
  }
  std::vector<double> values;
  for (std::size_t id : ids) {
    for (double v : sim.ProbeRecord(id)) values.push_back(v);
  }
  return values;
}

// Bit-identical as NaN-aware doubles.
void ExpectSameRecords(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(a[i])) {
      EXPECT_TRUE(std::isnan(b[i])) << i;
    } else {
      EXPECT_EQ(a[i], b[i]) << i;
    }
  }
}

// Recording changes nothing, and following the record at the same values gives the same run bit for bit.
TEST(ThermalChoices, FollowingItsOwnRecordIsTheSameRun) {
  const ThermalSettings settings = testing::SmallBuildSettings();
  ThermalSimulation free(settings), recording(settings), following(settings);
  const std::vector<double> plain = ChoiceBuild(free, 2000.0);
  recording.RecordChoices();
  const std::vector<double> recorded = ChoiceBuild(recording, 2000.0);
  auto choices = std::make_shared<const SolverChoices>(recording.TakeChoices());
  EXPECT_GT(choices->values.size(), 100u);
  following.FollowChoices(choices);
  ExpectSameRecords(plain, recorded);
  ExpectSameRecords(recorded, ChoiceBuild(following, 2000.0));
  // A run longer than the recorded one runs out of choices.
  ThermalSimulation longer(settings);
  longer.FollowChoices(choices);
  EXPECT_THROW(ChoiceBuild(longer, 2000.0, 4), InputError);
}

// The largest |d1 - 10 d2| over the readings against the largest |d1|, where d1 and d2 are the changes of the
// readings from `base` when a parameter moves by 10 delta and by delta (runs made by `run`): 0 for a response linear
// over that range, about 10 delta's share of curvature for a smooth one.
template <typename Run>
double NonLinearity(const std::vector<double>& base, const Run& run, double delta) {
  const std::vector<double> big = run(10.0 * delta), small = run(delta);
  double worst = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < base.size(); ++i) {
    if (std::isnan(base[i])) continue;
    const double d1 = big[i] - base[i], d2 = small[i] - base[i];
    worst = std::max(worst, std::abs(d1 - 10.0 * d2));
    largest = std::max(largest, std::abs(d1));
  }
  EXPECT_GT(largest, 0.0);
  return worst / largest;
}

// Following the record, the readings respond to the heat input, the convection and the table contact nearly linearly
// over changes of 0.1 % (heat) and 1 % (the losses): no switch of the solver moves them. Measured: 0.041, 0.00056 and
// 0.0093 (with the diagonal preconditioner instead of symmetric Gauss-Seidel: 0.042, 0.0026 and 0.0087; with the
// linear solves at 0.01 K instead of 0.001 K: 0.043, 0.045 and 0.051; free runs of this build,
// making their own choices, at 0.01 K: 0.21, 0.15 and 0.41). The heat's residue is the melt
// pool's: its readings at 1200-1740 degC, where the liquid's conductivity ramps fivefold across the mushy zone.
TEST(ThermalChoices, FollowedRunsRespondContinuously) {
  const ThermalSettings settings = testing::SmallBuildSettings();
  ThermalSimulation recording(settings);
  recording.RecordChoices();
  const std::vector<double> base = ChoiceBuild(recording, 2000.0);
  auto choices = std::make_shared<const SolverChoices>(recording.TakeChoices());
  auto follow = [&](const ThermalSettings& changed, double heat_w) {
    ThermalSimulation sim(changed);
    sim.FollowChoices(choices);
    return ChoiceBuild(sim, heat_w);
  };
  // The runs with one setting scaled by 1 + d.
  auto scaled = [&](double ThermalSettings::*member) {
    return [&, member](double d) {
      ThermalSettings changed = settings;
      changed.*member *= 1.0 + d;
      return follow(changed, 2000.0);
    };
  };
  EXPECT_LT(NonLinearity(base, [&](double d) { return follow(settings, 2000.0 * (1.0 + d)); }, 1e-4), 0.1);
  EXPECT_LT(NonLinearity(base, scaled(&ThermalSettings::convection_w_m2k), 1e-3), 0.01);
  EXPECT_LT(NonLinearity(base, scaled(&ThermalSettings::table_conductance_w_m2k), 1e-3), 0.1);
}

}  // namespace
}  // namespace waam::twin
