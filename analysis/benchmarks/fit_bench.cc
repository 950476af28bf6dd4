// Benchmarks of the model fits: CSW, speed-height power law, width-height quartic, void network with restarts and CV.
#include <filesystem>

#include <benchmark/benchmark.h>

#include "models/bead/csw_model.h"
#include "models/bead/speed_height_model.h"
#include "models/bead/width_height_model.h"
#include "models/core/csv.h"
#include "models/voids/void_length_baseline.h"
#include "models/voids/void_length_network.h"

namespace {
namespace m = waam::models;

waam::CsvTable Table(const char* name) {
  return waam::CsvTable::Read(std::filesystem::path(WAAM_SOURCE_DIR) / "models" / "data" / name);
}

m::DataSource Source() { return m::DataSource{"bench", {}, {}, 0, ""}; }

void BM_FitCsw(benchmark::State& state) {
  const waam::CsvTable t = Table("dai2020_csw_table1.csv");
  const m::CswSamples s{t.Numbers("travel_speed_mm_per_min"), t.Numbers("curvature_radius_mm"), t.Numbers("width_mm")};
  for (auto _ : state) benchmark::DoNotOptimize(m::FitCsw(s, Source()).ok);
}
BENCHMARK(BM_FitCsw)->Unit(benchmark::kMicrosecond);

void BM_FitSpeedHeightPowerLaw(benchmark::State& state) {
  const waam::CsvTable t = Table("nguyen2022_table18_bead_vs_speed.csv");
  const m::SpeedHeightSamples s{t.Numbers("travel_speed_mm_per_min"), t.Numbers("height_mm")};
  for (auto _ : state) benchmark::DoNotOptimize(m::FitSpeedHeight(s, Source()).ok);
}
BENCHMARK(BM_FitSpeedHeightPowerLaw)->Unit(benchmark::kMicrosecond);

void BM_FitWidthHeightQuartic(benchmark::State& state) {
  const waam::CsvTable t = Table("nguyen2022_table18_bead_vs_speed.csv");
  const m::WidthHeightSamples s{t.Numbers("height_mm"), t.Numbers("width_mm")};
  for (auto _ : state) benchmark::DoNotOptimize(m::FitWidthHeight(s, Source(), 4).ok);
}
BENCHMARK(BM_FitWidthHeightQuartic)->Unit(benchmark::kMicrosecond);

std::vector<m::JunctionSample> Junctions() {
  const waam::CsvTable t = Table("nguyen2022_appendixA1_junction_voids.csv");
  const auto eta = t.Numbers("eta"), l = t.Numbers("void_length_mm"), t1 = t.Numbers("theta1_deg"),
             t2 = t.Numbers("theta2_deg"), t3 = t.Numbers("theta3_deg"), t4 = t.Numbers("theta4_deg");
  std::vector<m::JunctionSample> out;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    out.push_back({m::Junction{static_cast<int>(eta[i]), {t1[i], t2[i], t3[i], t4[i]}}, l[i], ""});
  }
  return out;
}

// One network fit on all 63 junctions with the default options (7-7 tanh, Bayesian L2, 5 restarts).
void BM_TrainVoidNetwork(benchmark::State& state) {
  const auto samples = Junctions();
  m::VoidNetworkOptions options;
  options.restarts = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(m::TrainVoidLengthNetwork(samples, Source(), options).ok);
  state.counters["restarts"] = options.restarts;
}
BENCHMARK(BM_TrainVoidNetwork)->Arg(1)->Arg(5)->Unit(benchmark::kMillisecond);

// 5-fold cross-validation of the default network (5 trainings of 5 restarts each), what `waam fit void-length` runs.
void BM_VoidNetworkCrossValidation5Fold(benchmark::State& state) {
  const auto samples = Junctions();
  const m::VoidNetworkOptions options;
  const m::VoidLengthTrainer trainer = [&](const std::vector<m::JunctionSample>& training) {
    m::VoidNetworkFit fit = m::TrainVoidLengthNetwork(training, Source(), options);
    return std::unique_ptr<m::VoidLengthModel>(std::move(fit.model));
  };
  m::CrossValidationOptions cv;
  for (auto _ : state) benchmark::DoNotOptimize(m::CrossValidate(samples, trainer, cv).mae_mm);
}
BENCHMARK(BM_VoidNetworkCrossValidation5Fold)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_VoidBaselineCrossValidation5Fold(benchmark::State& state) {
  const auto samples = Junctions();
  const m::VoidLengthTrainer trainer = [&](const std::vector<m::JunctionSample>& training) {
    return std::unique_ptr<m::VoidLengthModel>(m::FitVoidLengthBaseline(training, Source()).model.release());
  };
  for (auto _ : state) benchmark::DoNotOptimize(m::CrossValidate(samples, trainer, {}).mae_mm);
}
BENCHMARK(BM_VoidBaselineCrossValidation5Fold)->Unit(benchmark::kMillisecond);

}  // namespace
