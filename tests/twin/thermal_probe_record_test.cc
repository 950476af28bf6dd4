// Probe records taken inside the solver's batches (ThermalSimulation::RecordProbes) against TemperatureAt queries.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "models/core/error.h"
#include "tests/twin/thermal_test_util.h"

namespace waam::twin {
namespace {

const std::vector<Eigen::Vector3d> kProbes = {{0, 10, -1}, {10, 0, -3}, {0, 0, 5}};  // plate, plate, third layer

// The small build in welds of 10 mm (whole micro steps, so that records close no micro step early), `record`
// called after every weld and every 1 s of cooling; returns the times.
template <typename Record>
std::vector<double> Build(ThermalSimulation& sim, const Record& record) {
  std::vector<double> times;
  for (int layer = 0; layer < 4; ++layer) {
    const double z = 2.0 * (layer + 1);
    const double x0 = layer % 2 == 0 ? -20.0 : 20.0;
    for (int piece = 0; piece < 4; ++piece) {
      const double a = x0 + (x0 < 0 ? 10.0 : -10.0) * piece, b = a + (x0 < 0 ? 10.0 : -10.0);
      sim.Weld(Eigen::Vector3d(a, 0, z), Eigen::Vector3d(b, 0, z), 4.0, 2.0, 2000.0, 1.25);
      times.push_back(sim.time_s());
      record();
    }
    for (int second = 0; second < 3; ++second) {
      sim.Cool(1.0);
      times.push_back(sim.time_s());
      record();
    }
  }
  return times;
}

// Single-rate stepping (every micro step solves the whole model): the records are exactly the temperatures
// TemperatureAt reads at the same times, NaN in the third layer until it is laid.
TEST(ThermalProbeRecord, SingleRateRecordsAreTheQueriedTemperatures) {
  ThermalSettings settings = testing::SmallBuildSettings();
  settings.far_step_s = 0.0;
  ThermalSimulation recorded(settings), queried(settings);
  for (const Eigen::Vector3d& p : kProbes) recorded.AddProbe(p);
  std::vector<std::size_t> ids;
  std::vector<std::vector<double>> values;
  Build(recorded, [&] { ids.push_back(recorded.RecordProbes()); });
  Build(queried, [&] {
    std::vector<double> v;
    for (const Eigen::Vector3d& p : kProbes) v.push_back(queried.TemperatureAt(p));
    values.push_back(v);
  });
  ASSERT_EQ(ids.size(), values.size());
  int nan = 0;
  for (std::size_t r = 0; r < ids.size(); ++r) {
    const std::vector<double> got = recorded.ProbeRecord(ids[r]);
    for (std::size_t p = 0; p < kProbes.size(); ++p) {
      if (std::isnan(values[r][p])) {
        EXPECT_TRUE(std::isnan(got[p])) << "record " << r << " probe " << p;
        ++nan;
      } else {
        EXPECT_EQ(got[p], values[r][p]) << "record " << r << " probe " << p;
      }
    }
  }
  EXPECT_GT(nan, 0) << "the third layer's probe reads no metal before it is laid";
  EXPECT_THROW(recorded.ProbeRecord(ids.size()), InputError);
  EXPECT_THROW(recorded.AddProbe(Eigen::Vector3d::Zero()), InputError) << "a probe added after a record";
}

// Multirate stepping: recording does not change the solution (the field is bit-identical to a run that records
// nothing), and each record lies within 3 % of the rise of the temperature single-rate stepping gives there (the
// multirate test's 2 % for a plate probe, plus the linear interpolation over the coarser levels' steps).
TEST(ThermalProbeRecord, MultirateRecordsFollowSingleRateWithoutChangingTheSolution) {
  ThermalSettings single = testing::SmallBuildSettings();
  single.far_step_s = 0.0;
  const ThermalSettings multi = testing::SmallBuildSettings();
  ThermalSimulation recorded(multi), plain(multi), reference(single);
  for (const Eigen::Vector3d& p : kProbes) recorded.AddProbe(p);
  std::vector<std::size_t> ids;
  std::vector<std::vector<double>> expected;
  Build(recorded, [&] { ids.push_back(recorded.RecordProbes()); });
  Build(plain, [] {});
  Build(reference, [&] {
    std::vector<double> v;
    for (const Eigen::Vector3d& p : kProbes) v.push_back(reference.TemperatureAt(p));
    expected.push_back(v);
  });
  for (std::size_t r = 0; r < ids.size(); ++r) {
    const std::vector<double> got = recorded.ProbeRecord(ids[r]);
    for (std::size_t p = 0; p < 2; ++p) {  // the plate probes
      const double rise = expected[r][p] - multi.initial_c;
      EXPECT_NEAR(got[p], expected[r][p], 0.03 * rise + 0.5) << "record " << r << " probe " << p;
    }
  }
  const TemperatureField a = recorded.Field(), b = plain.Field();
  ASSERT_EQ(a.temperature_c.size(), b.temperature_c.size());
  for (std::size_t i = 0; i < a.temperature_c.size(); ++i) {
    if (std::isnan(a.temperature_c[i])) continue;
    ASSERT_EQ(a.temperature_c[i], b.temperature_c[i]) << "cell " << i;
  }
}

}  // namespace
}  // namespace waam::twin
