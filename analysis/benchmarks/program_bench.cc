// Reading speed of the program readers (lines per second) on a 100,000-point program in each dialect, and the
// conversion of what was read into a plan. Run: build/analysis/benchmarks/waam_program_bench.
#include <algorithm>
#include <array>
#include <string>

#include <benchmark/benchmark.h>

#include "planner/kinematics/cell_motion.h"
#include "planner/program/abb_rapid.h"
#include "planner/program/fanuc_ls.h"
#include "planner/program/gcode.h"
#include "planner/program/kuka_krl.h"
#include "planner/program/program_plan.h"
#include "planner/program/program_reader.h"
#include "planner/program/robot_program.h"
#include "planner/program/yaskawa_jbi.h"

namespace {
using namespace waam::planner;

CellKinematics BenchCell() {
  CellKinematics cell;
  cell.arm = OpwArm::ArcMate100iC12();
  cell.X_FT.translation() = Eigen::Vector3d(400.0, 0.0, 0.0);
  cell.X_FT.linear() << 0, 0, 1, 0, -1, 0, 1, 0, 0;
  cell.X_WB.translation() = Eigen::Vector3d(1050.0, 0.0, 0.0);
  return cell;
}

// 200 layers of 500 points: a 1 mm-step zigzag over a 50 mm square, 1.5 mm layers.
const RobotProgram& BenchProgram() {
  static const RobotProgram program = [] {
    Plan plan;
    for (int l = 0; l < 200; ++l) {
      LayerPath layer;
      layer.index = l;
      for (int i = 0; i < 500; ++i) {
        PathPoint p;
        const int row = i / 50, col = i % 50;
        p.p_P = Eigen::Vector3d(-25.0 + (row % 2 ? 49 - col : col), -25.0 + 5.0 * row, 1.5 * (l + 1));
        p.weld = i > 0;
        p.speed_mm_s = p.weld ? 400.0 / 60.0 : 100.0;
        layer.points.push_back(p);
      }
      plan.layers.push_back(layer);
    }
    MotionOptions options;
    options.step_mm = 1e6;
    return BuildProgram(BenchCell(), PlanCellMotion(BenchCell(), plan, options, {}), "bench");
  }();
  return program;
}

// A JBI's station pulses per degree (tilt, rotation), written and read with the same values.
constexpr std::array<double, 2> kBenchStationPulsesPerDeg = {1365.3, 1137.8};

std::string Text(ProgramFormat format) {
  const CellKinematics cell = BenchCell();
  switch (format) {
    case ProgramFormat::kFanucLs: return ProgramToFanucLs(BenchProgram(), FanucLsOptions{});
    case ProgramFormat::kAbbRapid: {
      AbbRapidOptions options;
      options.X_RU = cell.X_WR.inverse() * ProgramUserFrame(cell);
      return ProgramToAbbRapid(BenchProgram(), options);
    }
    case ProgramFormat::kGcode: return ProgramToGcode(BenchProgram(), GcodeOptions{});
    case ProgramFormat::kKukaKrl: {
      KukaKrlOptions options;
      options.X_RU = cell.X_WR.inverse() * ProgramUserFrame(cell);
      const KukaKrlFiles files = ProgramToKukaKrl(BenchProgram(), options);
      return files.src + files.dat;
    }
    case ProgramFormat::kYaskawaJbi: {
      YaskawaJbiOptions options;
      options.X_RU = cell.X_WR.inverse() * ProgramUserFrame(cell);
      options.station_pulses_per_deg = kBenchStationPulsesPerDeg;
      return ProgramToYaskawaJbi(BenchProgram(), options);
    }
    default: return ProgramToCsv(BenchProgram());
  }
}

void BM_ReadProgram(benchmark::State& state) {
  const ProgramFormat format = static_cast<ProgramFormat>(state.range(0));
  const std::string text = Text(format);
  const auto lines = static_cast<std::int64_t>(std::count(text.begin(), text.end(), '\n'));
  JbiReadOptions jbi;
  jbi.station_pulses_per_deg = kBenchStationPulsesPerDeg;
  for (auto _ : state) benchmark::DoNotOptimize(ReadProgramText(text, "bench", format, GcodeReadOptions{}, jbi));
  state.SetItemsProcessed(state.iterations() * lines);  // items = lines
  state.SetLabel(std::string(waam::NameOf(format)) + ", " + std::to_string(lines) + " lines");
}
BENCHMARK(BM_ReadProgram)
    ->Arg(static_cast<int>(ProgramFormat::kCsv))
    ->Arg(static_cast<int>(ProgramFormat::kFanucLs))
    ->Arg(static_cast<int>(ProgramFormat::kAbbRapid))
    ->Arg(static_cast<int>(ProgramFormat::kKukaKrl))
    ->Arg(static_cast<int>(ProgramFormat::kYaskawaJbi))
    ->Arg(static_cast<int>(ProgramFormat::kGcode))
    ->Unit(benchmark::kMillisecond);

void BM_ProgramToPlan(benchmark::State& state) {
  const ParsedProgram program = ReadProgramText(Text(ProgramFormat::kFanucLs), "bench", ProgramFormat::kFanucLs);
  const CellKinematics cell = BenchCell();
  for (auto _ : state) benchmark::DoNotOptimize(ProgramToPlan(program, cell, ImportSettings{}));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(program.motions.size()));
}
BENCHMARK(BM_ProgramToPlan)->Unit(benchmark::kMillisecond);

}  // namespace
