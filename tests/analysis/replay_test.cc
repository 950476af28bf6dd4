// The process-log reader (dialects, reported rows, refused rows), the replay's metrics, and the round trip: a log
// made by the thermal model with seeded noise and known parameters, replayed and fitted back.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ceres/manifold.h>

#include "analysis/fit_command.h"
#include "analysis/fit_internal.h"
#include "analysis/replay_command.h"
#include "analysis/replay_synthetic.h"
#include "models/core/error.h"
#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

ReplaySection Section() {
  ReplaySection s;
  s.columns.power_w = "P";
  s.probes.push_back({"tc1", "T1", Eigen::Vector3d::Zero(), "replay.probes.tc1"});
  return s;
}

std::string Error(const std::string& text, const ReplaySection& section) {
  try {
    ParseReplayLog(text, section, "log.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ReplayLog, ReadsASemicolonLogWithDecimalCommasClockTimesAcrossMidnightAndAFrame) {
  ReplaySection s = Section();
  s.header_rows = 2;
  s.time_unit = LogTimeUnit::kClock;
  s.frame_offset_mm = {100.0, 0.0, 5.0};
  s.frame_rotation_deg = 90.0;
  const std::string text =
      "\xEF\xBB\xBFMachine;Cell 3\r\nExported;2024-05-01\r\n"
      "time;P;arc_on;x;y;z;T1\r\n"
      "2024-05-01 23:59:58;2100,5;1;10;0;2;25,5\r\n"
      "23:59:59;\"2000\";ON;11;0;2;26\r\n"
      "\r\n"
      "00:00:00,5;0;off;12;0;2;\r\n";
  const ReplayLog log = ParseReplayLog(text, s, "log.csv");
  ASSERT_EQ(log.time_s.size(), 3u);
  EXPECT_DOUBLE_EQ(log.time_s[1], 1.0);
  EXPECT_DOUBLE_EQ(log.time_s[2], 2.5) << "midnight is crossed, not time going backwards";
  EXPECT_DOUBLE_EQ(log.power_w[0], 2100.5) << "decimal comma with a semicolon delimiter";
  EXPECT_EQ(log.arc_on[1], 1);
  EXPECT_EQ(log.arc_on[2], 0);
  // Rotated 90 deg about z then offset: (10, 0, 2) -> (100, 10, 7).
  EXPECT_NEAR(log.head_mm[0].x(), 100.0, 1e-9);
  EXPECT_NEAR(log.head_mm[0].y(), 10.0, 1e-9);
  EXPECT_NEAR(log.head_mm[0].z(), 7.0, 1e-9);
  EXPECT_TRUE(std::isnan(log.probe_c[0][2]));
  ASSERT_EQ(log.issues.size(), 1u);
  EXPECT_EQ(log.issues[0].kind, "empty_probe_cell");
  EXPECT_EQ(log.issues[0].line, 7);
}

TEST(ReplayLog, ReportsAZeroFirstRowARepeatedTimeAndAGapWithoutUsingThem) {
  ReplaySection s = Section();
  s.columns.power_w.clear();
  s.columns.voltage_v = "U";
  s.columns.current_a = "I";
  s.time_unit = LogTimeUnit::kDayFraction;
  std::ostringstream text;
  text.precision(15);
  text << "time,U,I,arc_on,x,y,z,T1\n0,0,0,0,0,0,0,0\n";
  const double day = 86400.0;
  for (int t : {100, 101, 101, 102, 110, 111}) text << (45000.0 + t / day) << ",20,150,1,0,0,0,30\n";
  const ReplayLog log = ParseReplayLog(text.str(), s, "log.csv");
  ASSERT_EQ(log.time_s.size(), 5u) << "the zero row and the repeated time are left out";
  EXPECT_NEAR(log.time_s[4], 11.0, 1e-3) << "a spreadsheet date serial: times from the first row";
  EXPECT_DOUBLE_EQ(log.power_w[0], 3000.0);
  ASSERT_EQ(log.issues.size(), 3u);
  EXPECT_EQ(log.issues[0].kind, "zero_first_row");
  EXPECT_EQ(log.issues[1].kind, "repeated_time");
  EXPECT_EQ(log.issues[2].kind, "gap");
  EXPECT_EQ(log.gap_before[3], 1) << "102 s -> 110 s is longer than 3 x the median step";
}

TEST(ReplayLog, RefusesBadRowsNamingFileLineAndCell) {
  const ReplaySection s = Section();
  const std::string head = "time,P,arc_on,x,y,z,T1\n0,1000,1,0,0,0,20\n";
  EXPECT_THAT(Error("time,P,arc_on,x,y,T1\n0,1,1,0,0,20\n", s),
              HasSubstr("log.csv:1: no column 'z' (replay.columns.z)"));
  EXPECT_THAT(Error(head + "2,1000,1,0,0,0,20\n1,1000,1,0,0,0,20\n", s),
              HasSubstr("log.csv:4: time 1 s is before the previous row's 2 s (line 3)"));
  EXPECT_THAT(Error(head + "1,12a,1,0,0,0,20\n", s), HasSubstr("log.csv:3:2: column 'P': '12a' is not a number"));
  EXPECT_THAT(Error(head + "1,-5,1,0,0,0,20\n", s), HasSubstr("log.csv:3:2: column 'P': negative power -5 W"));
  EXPECT_THAT(Error(head + "1,5,maybe,0,0,0,20\n", s), HasSubstr("log.csv:3:3: column 'arc_on': 'maybe'"));
  EXPECT_THAT(Error(head + "1,5,1,0\n", s), HasSubstr("log.csv:3:5: the row has 4 cells"));
  EXPECT_THAT(Error(head, s), HasSubstr("1 data rows"));
}

TEST(ReplayErrors, MatchHandComputedValuesAndLeaveOutMissingRows) {
  const std::vector<double> t = {0, 1, 2, 3};
  const std::vector<double> measured = {10, 20, NAN, 40};
  const std::vector<double> simulated = {12, 17, 5, 40};
  const ReplayErrors e = CompareProbe(t, measured, simulated, 0.0, 3.0);
  EXPECT_EQ(e.n, 3u);
  EXPECT_NEAR(e.rmse_c, std::sqrt((4.0 + 9.0) / 3.0), 1e-12);
  EXPECT_NEAR(e.mae_c, 5.0 / 3.0, 1e-12);
  EXPECT_NEAR(e.mape_pct, 100.0 * (0.2 + 0.15) / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(e.max_error_c, 3.0);
  EXPECT_DOUBLE_EQ(e.max_error_time_s, 1.0);
  EXPECT_DOUBLE_EQ(e.peak_measured_c, 40.0);
  const ReplayErrors held = CompareProbe(t, measured, simulated, 0.5, 3.0, true);
  EXPECT_EQ(held.n, 1u) << "outside [0.5, 3]: only t = 0";
}

// A replay scenario for the round trip: a 40 mm wall on a 70 x 30 x 6 mm mild-steel plate, two thermocouples;
// `thermal_extra`: more lines of its thermal: section.
std::string RoundTripScenario(const std::string& thermal_extra = "") {
  return "name: replay_round_trip\n"
         "part:\n  generator: {type: box, size_mm: [40, 6, 4]}\n"
         "slicing:\n  layer_height_mm: 2\npath:\n  pattern: zigzag\n  bead_width_mm: 6\n"
         "process:\n  travel_speed_mm_min: 480\n  wire_feed_mm_min: 3200\n"
         "  arc: {power_w: 2000, efficiency: 0.84}\n"
         "thermal:\n  material: mild_steel\n  substrate: {size_mm: [70, 30, 6]}\n  cell_mm: 2\n"
         "  convection_w_m2k: 10\n" + thermal_extra +
         "replay:\n  log: wall.csv\n  columns: {power_w: power_w}\n  bead: {width_mm: 6, height_mm: 2}\n"
         "  probes:\n    near: {column: T1, at_mm: [0, 7, -1]}\n    far: {column: T2, at_mm: [25, -10, -4]}\n";
}

// Writes the scenario and a log the model made with `truth` (noise 1 degC, seed 7); returns the scenario path.
fs::path WriteRoundTrip(const fs::path& dir, const ThermalParameters& truth,
                        const std::string& thermal_extra = "") {
  const fs::path scenario = dir / "scenario.yaml";
  std::ofstream(scenario) << RoundTripScenario(thermal_extra);
  WallBuildSpec spec;
  spec.layers = 2;
  spec.length_mm = 40.0;
  spec.dwell_s = 20.0;
  spec.tail_s = 90.0;
  ReplayLog rows = WallBuildLog(spec);
  const std::vector<std::string> columns = {"T1", "T2"};
  const std::vector<std::vector<double>> blank(2, std::vector<double>(rows.time_s.size(), NAN));
  std::ofstream(dir / "wall.csv") << ReplayLogCsv(rows, columns, blank, 0.0, 1);
  const Scenario loaded = LoadScenario(scenario);
  const ReplayModel model = MakeReplayModel(loaded, rows);
  const ReplaySimulation sim = SimulateReplay(model, truth);
  std::ofstream(dir / "wall.csv") << ReplayLogCsv(rows, columns, sim.probe_c, 1.0, 7);
  return scenario;
}

// The replay's model takes the scenario's heat source as `waam thermal` does (it once kept the defaults: a replay
// with thermal.heat_source: uniform_bead ran the double ellipsoid).
TEST(ReplayModel, TakesTheScenariosHeatSourcePoolAndLiquidFactor) {
  const fs::path dir = cli_test::TempDir("replay_heat_source");
  const fs::path scenario = dir / "scenario.yaml";
  std::ofstream(scenario) << RoundTripScenario(
      "  heat_source: uniform_bead\n  pool: {depth_beads: 1.5, front_widths: 0.7, rear_widths: 3}\n"
      "  liquid_conductivity_factor: 2\n");
  std::ofstream(dir / "wall.csv") << "";  // the scenario's log must exist; the model is made from `rows` below
  WallBuildSpec spec;
  spec.layers = 1;
  spec.length_mm = 40.0;
  const ReplayLog rows = WallBuildLog(spec);
  const ReplayModel model = MakeReplayModel(LoadScenario(scenario), rows);
  EXPECT_EQ(model.settings.heat_source, twin::HeatSourceShape::kUniformBead);
  EXPECT_DOUBLE_EQ(model.settings.pool_depth_beads, 1.5);
  EXPECT_DOUBLE_EQ(model.settings.pool_front_widths, 0.7);
  EXPECT_DOUBLE_EQ(model.settings.pool_rear_widths, 3.0);
  EXPECT_DOUBLE_EQ(model.settings.liquid_conductivity_factor, 2.0);
}

TEST(ReplayRoundTrip, AReplayAtTheTrueParametersMatchesTheLogToItsNoise) {
  const fs::path dir = cli_test::TempDir("replay_truth");
  ThermalParameters truth;
  truth.efficiency = 0.7;
  truth.convection_w_m2k = 25.0;
  const fs::path scenario = WriteRoundTrip(dir, truth);
  ReplayModel model = LoadReplayModel(scenario, {});
  const ReplaySimulation sim = SimulateReplay(model, truth);
  const nlohmann::json errors = ReplayErrorsJson(model, sim, 0.0, model.log.time_s.back());
  // The log holds the model's own temperatures (written to 0.01 degC) plus N(0, 1 degC) noise.
  EXPECT_NEAR(errors["overall"]["rmse_c"].get<double>(), 1.0, 0.1);
  EXPECT_GT(errors["probes"]["near"]["peak_measured_c"].get<double>(), 100.0) << "the probe must see the welds";
}

// A replay of a window drives the log on until the solver's own batches hold the window's end: its probes up to
// there are the whole log's, bit for bit, and continued it is the whole log's replay (the fit's reported figures
// continue its replays). Stopping at the window's end instead ends a batch there and moves later readings.
TEST(ReplayRun, AWindowsReplayIsTheWholeLogsUpToItsEndAndContinuesAsIt) {
  const fs::path dir = cli_test::TempDir("replay_window_prefix");
  ThermalParameters truth;
  truth.efficiency = 0.7;
  const ReplayModel model = LoadReplayModel(WriteRoundTrip(dir, truth), {});
  const ReplaySimulation whole = SimulateReplay(model, model.parameters);
  const double end_s = 28.0;  // during the second layer (welded from 25 to 30 s)
  ReplayRun run(model, model.parameters);
  run.AdvanceThrough(end_s);
  const std::vector<std::vector<double>> window = run.ProbesTo(end_s);
  const std::vector<double>& time_s = model.log.time_s;
  std::size_t compared = 0, moved = 0;
  const ReplaySimulation stopped = SimulateReplay(model, model.parameters, end_s);
  for (std::size_t p = 0; p < model.probes.size(); ++p) {
    for (std::size_t i = 0; i < time_s.size(); ++i) {
      if (time_s[i] > end_s) {
        EXPECT_TRUE(std::isnan(window[p][i])) << "row " << i;
        continue;
      }
      if (std::isnan(whole.probe_c[p][i])) continue;
      EXPECT_EQ(window[p][i], whole.probe_c[p][i]) << "probe " << p << " row " << i;
      ++compared;
      moved += stopped.probe_c[p][i] != whole.probe_c[p][i] ? 1 : 0;
    }
  }
  EXPECT_GT(compared, 40u);
  EXPECT_GT(moved, 0u) << "stopping at the window's end ends a batch there: the test must tell the two apart";
  run.AdvanceTo(std::numeric_limits<double>::infinity());
  const ReplaySimulation continued = run.Result();
  for (std::size_t p = 0; p < model.probes.size(); ++p) {
    for (std::size_t i = 0; i < time_s.size(); ++i) {
      if (std::isnan(whole.probe_c[p][i])) {
        EXPECT_TRUE(std::isnan(continued.probe_c[p][i]));
      } else {
        EXPECT_EQ(continued.probe_c[p][i], whole.probe_c[p][i]) << "probe " << p << " row " << i;
      }
    }
  }
  EXPECT_EQ(continued.energy.stored_j, whole.energy.stored_j);
}

// The log's values for the round trip: efficiency 0.7 and convection 25 W/(m^2 K).
ThermalParameters RoundTripTruth() {
  ThermalParameters truth;
  truth.efficiency = 0.7;
  truth.convection_w_m2k = 25.0;
  return truth;
}

// The round trip's two-parameter fit options: efficiency and convection on the first 60 s of a log made in `dir` at
// `truth`, written to `dir`/`output`.
FitOptions RoundTripFit(const fs::path& dir, const std::string& output,
                        const ThermalParameters& truth = RoundTripTruth()) {
  FitOptions options;
  options.model = waam::analysis::FitModel::kThermal;
  options.data = WriteRoundTrip(dir, truth);
  options.output = dir / output;
  options.free = {"efficiency", "convection"};
  options.window = "0:60";
  options.jacobian_cell_mm = 0.0;  // every Jacobian on the scenario's grid (auto takes 3 mm here: below)
  return options;
}

TEST(ReplayRoundTrip, FitRecoversEfficiencyAndConvectionFromTheFirstHalf) {
  const FitOptions options = RoundTripFit(cli_test::TempDir("replay_fit"), "fitted.json");
  const fs::path& scenario = options.data;
  std::ostringstream out;
  const FitOutcome outcome = RunFit(options, out);
  ASSERT_TRUE(outcome.ok) << out.str();
  std::cout << out.str();
  const nlohmann::json fitted = cli_test::ReadJson(options.output);
  EXPECT_NEAR(fitted["fitted"]["efficiency"].get<double>(), 0.7, 0.01) << out.str();
  EXPECT_NEAR(fitted["fitted"]["convection"].get<double>(), 25.0, 5.0) << out.str();
  EXPECT_LT(fitted["held_out"]["overall"]["rmse_c"].get<double>(), 1.5) << "the held-out rows are predicted";
  EXPECT_GT(fitted["start_held_out"]["rmse_c"].get<double>(), 5.0) << "and the start values did not predict them";
  // The fitted file replays: its parameters replace the scenario's.
  const ReplayModel model = LoadReplayModel(scenario, {}, options.output);
  EXPECT_NEAR(model.parameters.efficiency, fitted["parameters"]["efficiency"].get<double>(), 1e-12);
  // Two thermocouples under the welds tell efficiency from convection: both determined, to within the tolerances.
  const nlohmann::json& id = fitted["identifiability"];
  ASSERT_TRUE(id.is_object()) << out.str();
  EXPECT_TRUE(id["undetermined"].empty()) << id.dump();
  EXPECT_NEAR(id["noise_c"].get<double>(), 1.0, 0.2) << "the residual is the log's noise";
  EXPECT_LT(id["standard_deviation"]["efficiency"].get<double>(), 0.01) << id.dump();
  EXPECT_LT(id["standard_deviation"]["convection"].get<double>(), 5.0) << id.dump();
  EXPECT_TRUE(fitted["prior"].is_null());
  // No line search's Jacobians (Ceres' bounds would add n + 1 replays at every point tried): at most one per point,
  // the start of each Ceres run and each candidate tried.
  const nlohmann::json& solver = fitted["solver"];
  EXPECT_LE(solver["jacobian_evaluations"].get<int>(),
            solver["residual_evaluations"].get<int>() + solver["runs"].get<int>());
  // The fit ended at an accepted point whose Gauss-Newton step promised less than the function tolerance, without
  // trying that step: every candidate tried was accepted.
  EXPECT_EQ(solver["message"], "the Gauss-Newton step from the last accepted point promised to lower the cost by less "
                               "than the function tolerance");
  EXPECT_EQ(solver["unsuccessful_steps"].get<int>(), 0) << solver.dump();
}

// A log whose air takes less heat than the scenario's radiation alone (made with emissivity 0.2 and no convection;
// the fit keeps the scenario's emissivity) drives convection below its bound 0: the fit holds it within 1 % of its
// scale of the bound once the Gauss-Newton step would cross it, fits the efficiency with it held, and reports both.
TEST(ReplayRoundTrip, AParameterTheDataPushesAcrossItsBoundIsHeldThere) {
  ThermalParameters truth = RoundTripTruth();
  truth.convection_w_m2k = 0.0;
  truth.emissivity = 0.2;
  const FitOptions options = RoundTripFit(cli_test::TempDir("replay_fit_hold"), "fitted.json", truth);
  std::ostringstream out;
  ASSERT_TRUE(RunFit(options, out).ok) << out.str();
  std::cout << out.str();
  const nlohmann::json fitted = cli_test::ReadJson(options.output);
  EXPECT_EQ(fitted["solver"]["held_at_bound"], nlohmann::json::array({"convection"})) << out.str();
  EXPECT_EQ(fitted["at_bound"], nlohmann::json::array({"convection"})) << out.str();
  EXPECT_LE(fitted["fitted"]["convection"].get<double>(), 0.1) << out.str();
  EXPECT_NEAR(fitted["fitted"]["efficiency"].get<double>(), 0.7, 0.03) << out.str();
}

// A strong prior holds the free parameters at the start values (efficiency 0.84, h = 10) against the log's 0.7 and
// 25; a weak one leaves the fit to the data. The prior's part of the cost is not counted as noise.
TEST(ReplayRoundTrip, APriorPullsTowardTheStartValuesWithItsStatedWeight) {
  const fs::path dir = cli_test::TempDir("replay_fit_prior");
  FitOptions options = RoundTripFit(dir, "strong.json");
  options.prior_weight = 1e5;
  std::ostringstream out;
  ASSERT_TRUE(RunFit(options, out).ok) << out.str();
  const nlohmann::json strong = cli_test::ReadJson(options.output);
  EXPECT_NEAR(strong["fitted"]["efficiency"].get<double>(), 0.84, 2e-3) << out.str();
  EXPECT_NEAR(strong["fitted"]["convection"].get<double>(), 10.0, 0.2) << out.str();
  EXPECT_EQ(strong["prior"]["weight_c"].get<double>(), 1e5);
  EXPECT_EQ(strong["prior"]["toward"]["convection"].get<double>(), 10.0);
  EXPECT_GT(strong["identifiability"]["noise_c"].get<double>(), 5.0) << "the start values do not fit the log";
  options.output = dir / "weak.json";
  options.prior_weight = 1.0;
  ASSERT_TRUE(RunFit(options, out).ok) << out.str();
  const nlohmann::json weak = cli_test::ReadJson(options.output);
  EXPECT_NEAR(weak["fitted"]["efficiency"].get<double>(), 0.7, 0.01) << out.str();
  EXPECT_NEAR(weak["identifiability"]["noise_c"].get<double>(), 1.0, 0.2) << out.str();
}

// The identifiability report against closed forms: orthogonal Jacobian columns give s * scale / |column| and no
// correlation; nearly parallel ones a correlation near -1, both undetermined, the weakest combination along
// (1, -1) in scaled units; a prior W adds W^2 to J^T J.
TEST(ThermalIdentifiability, MatchesTheGaussNewtonCovarianceOfASmallJacobian) {
  internal::IdentifiabilityInput in;
  in.names = {"a", "b"};
  in.scales = {1.0, 10.0};
  in.values = {0.5, 21.0};
  in.m = 4;
  in.jacobian = {3, 0, 0, 4, 0, 0, 0, 0};  // columns (3, 0, 0, 0) and (0, 4, 0, 0)
  in.data_cost = 0.5 * 2.0 * 4.0;          // s^2 = 2 cost / (m - n) = 4
  nlohmann::json id = internal::ThermalIdentifiability(in);
  EXPECT_NEAR(id["noise_c"].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(id["standard_deviation"]["a"].get<double>(), 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(id["standard_deviation"]["b"].get<double>(), 2.0 * 10.0 / 4.0, 1e-12);
  EXPECT_NEAR(id["correlation"]["a"]["b"].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(id["condition_number"].get<double>(), 1.0, 1e-12);
  EXPECT_EQ(id["undetermined"], nlohmann::json::array({"a"})) << "sd 0.67 of 0.5 (> 25 %), 5 of 21 (< 25 %)";
  in.prior_weight = 4.0;
  id = internal::ThermalIdentifiability(in);
  EXPECT_NEAR(id["standard_deviation"]["a"].get<double>(), 2.0 / 5.0, 1e-12) << "sqrt(9 + 16)";
  EXPECT_NEAR(id["condition_number"].get<double>(), 1.0, 1e-12) << "the data's own";
  in.prior_weight = 0.0;
  in.values = {5.0, 200.0};
  in.jacobian = {1, 1, 1, 1.01, 1, 1, 1, 0.99};  // nearly parallel columns
  id = internal::ThermalIdentifiability(in);
  EXPECT_LT(id["correlation"]["a"]["b"].get<double>(), -0.99);
  EXPECT_GT(id["condition_number"].get<double>(), 1e3);
  const double wa = id["weakest"]["a"].get<double>(), wb = id["weakest"]["b"].get<double>();
  EXPECT_GT(wa, 0.0);
  EXPECT_NEAR(wb / in.scales[1], -wa, 0.02 * wa) << "along (1, -1) in scaled units";
  EXPECT_EQ(id["undetermined"].size(), 2u) << id.dump();
  in.jacobian = {3, 0, 0, 0, 0, 0, 0, 0};  // b not felt: blind, a as alone
  in.values = {0.5, 21.0};
  id = internal::ThermalIdentifiability(in);
  EXPECT_EQ(id["blind"], nlohmann::json::array({"b"}));
  EXPECT_FALSE(id["standard_deviation"].contains("b"));
  EXPECT_NEAR(id["standard_deviation"]["a"].get<double>(), std::sqrt(2.0 * 4.0 / 3.0) / 3.0, 1e-12) << "m - n = 3";
  EXPECT_EQ(id["undetermined"], nlohmann::json::array({"a", "b"}));
}

// The fit's maps from Ceres' unbounded u to the scaled parameters: x(u(x)) = x inside the bounds, dx/du equal to a
// central difference, x strictly inside the bounds and dx/du > 0 even far out in u, a start on a bound moved inside.
TEST(ThermalFitMap, RoundTripsAndItsSlopeMatchesAFiniteDifference) {
  const internal::ParameterMap lower{0.0, std::numeric_limits<double>::infinity()};  // convection, contact
  const internal::ParameterMap two{0.2, 1.0};                                          // efficiency
  for (const auto& map : {lower, two}) {
    for (const double x : {0.21, 0.5, 0.84, 0.99}) {
      EXPECT_NEAR(map.ToScaled(map.ToFree(x)), x, 1e-12) << "lo " << map.lo;
    }
    for (const double u : {-8.0, -1.0, 0.0, 0.7, 3.0}) {
      const double h = 1e-6;
      const double fd = (map.ToScaled(u + h) - map.ToScaled(u - h)) / (2.0 * h);
      EXPECT_NEAR(map.Slope(u), fd, 1e-7 * std::max(1.0, std::abs(fd))) << "u " << u << " lo " << map.lo;
      EXPECT_GT(map.Slope(u), 0.0) << "a gradient at every u";
      EXPECT_GT(map.ToScaled(u), map.lo);
    }
  }
  EXPECT_NEAR(lower.ToScaled(lower.ToFree(300.0)), 300.0, 1e-9) << "no upper bound";
  EXPECT_LT(two.ToScaled(30.0), 1.0);
  EXPECT_EQ(two.ToScaled(1e3), 1.0) << "the logistic saturates, never overflows";
  EXPECT_EQ(two.ToScaled(-1e3), 0.2);
  EXPECT_NEAR(lower.ToScaled(lower.ToFree(0.0)), internal::kStartInside, 1e-15) << "a start on the bound";
  EXPECT_NEAR(two.ToScaled(two.ToFree(1.0)), 1.0 - internal::kStartInside, 1e-12);
  EXPECT_NEAR(two.ToScaled(two.ToFree(0.1)), 0.2 + internal::kStartInside, 1e-12) << "beyond the bound";
}

// Ceres' steps in u: each coordinate capped at kMaxFreeStep; a held coordinate is out of the tangent space and stays.
TEST(ThermalFitMap, TheStepIsCappedAndAHeldCoordinateStays) {
  std::unique_ptr<ceres::Manifold> step(internal::NewCappedStep(3, {false, true, false}));
  ASSERT_EQ(step->AmbientSize(), 3);
  ASSERT_EQ(step->TangentSize(), 2);
  const double u[3] = {1.0, -5.0, 0.5};
  const double delta[2] = {10.0, -0.25};
  double out[3];
  ASSERT_TRUE(step->Plus(u, delta, out));
  EXPECT_EQ(out[0], 1.0 + internal::kMaxFreeStep);
  EXPECT_EQ(out[1], -5.0) << "held";
  EXPECT_EQ(out[2], 0.25);
  double back[2];
  ASSERT_TRUE(step->Minus(out, u, back));
  EXPECT_EQ(back[0], internal::kMaxFreeStep);
  EXPECT_EQ(back[1], -0.25);
  double plus[6], minus[6];
  ASSERT_TRUE(step->PlusJacobian(u, plus));
  ASSERT_TRUE(step->MinusJacobian(u, minus));
  EXPECT_EQ(std::vector<double>(plus, plus + 6), (std::vector<double>{1, 0, 0, 0, 0, 1}));  // 3 x 2
  EXPECT_EQ(std::vector<double>(minus, minus + 6), (std::vector<double>{1, 0, 0, 0, 0, 1}));  // 2 x 3
}

// The identifiability report is in physical (scaled) units whatever variable Ceres moves: the report of J_x equals
// the report of J_u = J_x diag(dx/du) mapped back by the delta method, sd_x = dx/du sd_u, same correlations.
TEST(ThermalIdentifiability, IsTheSameInPhysicalUnitsAsInCeresVariables) {
  const internal::ParameterMap map_a{0.2, 1.0}, map_b{0.0, std::numeric_limits<double>::infinity()};
  const double u_a = map_a.ToFree(0.75), u_b = map_b.ToFree(2.0);  // efficiency 0.75, convection 20 (scale 10)
  const double slope_a = map_a.Slope(u_a), slope_b = map_b.Slope(u_b);
  internal::IdentifiabilityInput x_in;
  x_in.names = {"efficiency", "convection"};
  x_in.scales = {1.0, 10.0};
  x_in.values = {0.75, 20.0};
  x_in.m = 4;
  x_in.jacobian = {300, 2, 250, -1, 100, -3, 40, -2.5};  // degC per scaled unit
  x_in.data_cost = 0.5 * 2.0 * 1.0;                      // s = 1 degC
  internal::IdentifiabilityInput u_in = x_in;
  u_in.scales = {1.0, 1.0};
  for (std::size_t r = 0; r < x_in.m; ++r) u_in.jacobian[2 * r] *= slope_a, u_in.jacobian[2 * r + 1] *= slope_b;
  const nlohmann::json in_x = internal::ThermalIdentifiability(x_in);
  const nlohmann::json in_u = internal::ThermalIdentifiability(u_in);
  EXPECT_NEAR(in_x["standard_deviation"]["efficiency"].get<double>(),
              slope_a * in_u["standard_deviation"]["efficiency"].get<double>(), 1e-12);
  EXPECT_NEAR(in_x["standard_deviation"]["convection"].get<double>(),
              10.0 * slope_b * in_u["standard_deviation"]["convection"].get<double>(), 1e-9);
  EXPECT_NEAR(in_x["correlation"]["efficiency"]["convection"].get<double>(),
              in_u["correlation"]["efficiency"]["convection"].get<double>(), 1e-12);
  // Closed form for the efficiency's: s^2 (J^T J)^-1 of the 2 x 2 normal matrix in x.
  double a = 0, b = 0, c = 0;
  for (std::size_t r = 0; r < 4; ++r) {
    const double ja = x_in.jacobian[2 * r], jb = x_in.jacobian[2 * r + 1];
    a += ja * ja, b += ja * jb, c += jb * jb;
  }
  EXPECT_NEAR(in_x["standard_deviation"]["efficiency"].get<double>(), std::sqrt(c / (a * c - b * b)), 1e-12);
  EXPECT_NEAR(in_x["standard_deviation"]["convection"].get<double>(), 10.0 * std::sqrt(a / (a * c - b * b)), 1e-9);
}

// Started on the bounds (convection 0, its lower bound; efficiency 0.99, next to its upper one 1), where a clamped
// parameter stepping past its bound had a zero Jacobian column and stayed there: the maps keep a gradient, so the
// fit walks back to the log's values (efficiency 0.7, convection 25 W/(m^2 K)), nothing at a bound or blind.
TEST(ReplayRoundTrip, AFitStartedOnTheBoundsRecoversTheTrueValues) {
  FitOptions options = RoundTripFit(cli_test::TempDir("replay_fit_bounds"), "fitted.json");
  options.overrides = {"thermal.convection_w_m2k=0", "process.arc.efficiency=0.99"};
  std::ostringstream out;
  ASSERT_TRUE(RunFit(options, out).ok) << out.str();
  const nlohmann::json fitted = cli_test::ReadJson(options.output);
  EXPECT_EQ(fitted["start"]["convection"].get<double>(), 0.0);
  EXPECT_NEAR(fitted["fitted"]["efficiency"].get<double>(), 0.7, 0.01) << out.str();
  EXPECT_NEAR(fitted["fitted"]["convection"].get<double>(), 25.0, 5.0) << out.str();
  EXPECT_TRUE(fitted["at_bound"].empty()) << out.str();
  EXPECT_TRUE(fitted["identifiability"]["blind"].empty()) << out.str();
  EXPECT_LT(fitted["held_out"]["overall"]["rmse_c"].get<double>(), 1.5) << out.str();
}

// The clamps' conductance as a free parameter (--free clamps: one factor on every thermal.clamps[] conductance): a
// clamp over the plate's end near the far thermocouple, 1000 W/(m^2 K) in the scenario, 3000 in the log (factor 3).
// Fitted with the efficiency on the first 60 s, the factor comes back and the fitted file replays with it.
TEST(ReplayRoundTrip, FitRecoversTheClampsConductanceFactor) {
  const fs::path dir = cli_test::TempDir("replay_fit_clamps");
  ThermalParameters truth;
  truth.efficiency = 0.7;
  truth.convection_w_m2k = 10.0;
  truth.clamp_factor = 3.0;
  FitOptions options;
  options.model = waam::analysis::FitModel::kThermal;
  options.data =
      WriteRoundTrip(dir, truth, "  clamps:\n    - {centre_mm: [28, 0], size_mm: [10, 24], conductance_w_m2k: 1000}\n");
  options.output = dir / "fitted.json";
  options.free = {"efficiency", "clamps"};
  options.window = "0:60";
  std::ostringstream out;
  ASSERT_TRUE(RunFit(options, out).ok) << out.str();
  std::cout << out.str();
  const nlohmann::json fitted = cli_test::ReadJson(options.output);
  EXPECT_EQ(fitted["start"]["clamps"].get<double>(), 1.0);
  EXPECT_NEAR(fitted["fitted"]["efficiency"].get<double>(), 0.7, 0.01) << out.str();
  EXPECT_NEAR(fitted["fitted"]["clamps"].get<double>(), 3.0, 0.1) << out.str();
  EXPECT_LT(fitted["held_out"]["overall"]["rmse_c"].get<double>(), 1.5) << out.str();
  const double factor = fitted["parameters"]["clamp_conductance_factor"].get<double>();
  EXPECT_EQ(factor, fitted["fitted"]["clamps"].get<double>());
  bool set_line = false;
  for (const auto& line : fitted["set"]) {
    set_line = set_line || line.get<std::string>().rfind("thermal.clamp_conductance_factor=", 0) == 0;
  }
  EXPECT_TRUE(set_line) << fitted["set"].dump();
  // The reported window and held-out errors are those of a fresh replay of the fitted file (`waam thermal replay
  // --parameters fitted.json`), not of the fit's own replay continued from the window's end.
  const ReplayModel refit = LoadReplayModel(options.data, {}, options.output);
  EXPECT_NEAR(refit.parameters.clamp_factor, factor, 1e-12);
  const ReplaySimulation fresh = SimulateReplay(refit, refit.parameters);
  EXPECT_NEAR(fitted["window"]["overall"]["rmse_c"].get<double>(),
              ReplayErrorsJson(refit, fresh, 0.0, 60.0)["overall"]["rmse_c"].get<double>(), 1e-9);
  EXPECT_NEAR(fitted["held_out"]["overall"]["rmse_c"].get<double>(),
              ReplayErrorsJson(refit, fresh, 0.0, 60.0, true)["overall"]["rmse_c"].get<double>(), 1e-9);
  // The scenario key scales the clamps as the fitted factor does: a replay with --set at the log's factor is the noise.
  const ReplayModel model = LoadReplayModel(options.data, {"thermal.clamp_conductance_factor=3"});
  ThermalParameters at_truth = model.parameters;
  at_truth.efficiency = 0.7;
  EXPECT_EQ(at_truth.clamp_factor, 3.0);
  const nlohmann::json errors = ReplayErrorsJson(model, SimulateReplay(model, at_truth), 0.0, model.log.time_s.back());
  EXPECT_NEAR(errors["overall"]["rmse_c"].get<double>(), 1.0, 0.1);
}

// The round trip's one-stage fit and the same fit changed by `change`: their fitted.json documents (one, two), the
// output of both in `out`.
std::pair<nlohmann::json, nlohmann::json> OneStageAndChanged(const std::string& name,
                                                             const std::function<void(FitOptions&)>& change,
                                                             std::ostringstream& out) {
  const fs::path dir = cli_test::TempDir(name);
  FitOptions options = RoundTripFit(dir, "one_stage.json");
  EXPECT_TRUE(RunFit(options, out).ok) << out.str();
  options.output = dir / "changed.json";
  change(options);
  EXPECT_TRUE(RunFit(options, out).ok) << out.str();
  std::cout << out.str();
  return {cli_test::ReadJson(dir / "one_stage.json"), cli_test::ReadJson(options.output)};
}

// Coarse to fine (--coarse-cell 4 on the 2 mm grid): the coarse stage only chooses the start of the fit on the
// scenario's grid, so it ends at that grid's own answer: the one-stage fit's values within the tolerances' reach.
TEST(ReplayRoundTrip, CoarseToFineFitEndsAtTheOneStageFitsValues) {
  std::ostringstream out;
  const auto [one, two] =
      OneStageAndChanged("replay_fit_coarse", [](FitOptions& o) { o.coarse_cell_mm = 4.0; }, out);
  ASSERT_TRUE(two["coarse"].is_object()) << out.str();
  EXPECT_TRUE(two["coarse"]["used"].get<bool>()) << out.str();
  EXPECT_NEAR(two["fitted"]["efficiency"].get<double>(), one["fitted"]["efficiency"].get<double>(), 2e-3) << out.str();
  EXPECT_NEAR(two["fitted"]["convection"].get<double>(), one["fitted"]["convection"].get<double>(), 1.0) << out.str();
  EXPECT_NEAR(two["fitted"]["efficiency"].get<double>(), 0.7, 0.01) << out.str();
  EXPECT_LT(two["held_out"]["overall"]["rmse_c"].get<double>(), 1.5) << out.str();
}

// Jacobians differenced on a coarser grid (--jacobian-cell auto, the default: 3 mm on the 2 mm grid, which holds the
// 6 mm bead and the 6 mm plate in two cells) with the residuals on the scenario's: the fit ends at the one-stage
// fit's values with fewer replays on the scenario's grid, judged converged by the coarse Jacobian's Gauss-Newton step,
// whose Jacobian the identifiability report then uses.
TEST(ReplayRoundTrip, JacobiansOnACoarserGridEndAtTheOneStageFitsValues) {
  std::ostringstream out;
  const auto [one, two] = OneStageAndChanged(
      "replay_fit_jacobian_grid", [](FitOptions& o) { o.jacobian_cell_mm = kAutoJacobianCell; }, out);
  EXPECT_EQ(FitOptions{}.jacobian_cell_mm, kAutoJacobianCell) << "auto is the default";
  EXPECT_EQ(two["jacobian_cell_mm"], 3.0) << out.str();
  EXPECT_TRUE(one["jacobian_cell_mm"].is_null()) << out.str();
  EXPECT_NE(out.str().find("Jacobians on a 3 mm grid, the residuals on the scenario's 2 mm (--jacobian-cell auto"),
            std::string::npos)
      << out.str();
  EXPECT_GE(two["solver"]["jacobians"]["coarse"].get<int>(), 3) << out.str();
  EXPECT_LT(two["solver"]["replays"].get<int>(), one["solver"]["replays"].get<int>()) << out.str();
  EXPECT_GT(two["solver"]["coarse_replays"].get<int>(), 0) << out.str();
  EXPECT_EQ(two["solver"]["jacobians"]["differenced"].get<int>(), 0) << out.str();
  EXPECT_NE(two["solver"]["message"].get<std::string>().find("(its Jacobian on the coarser grid) promised"),
            std::string::npos)
      << out.str();
  EXPECT_EQ(two["identifiability"]["jacobian_cell_mm"], 3.0) << out.str();
  EXPECT_EQ(one["identifiability"]["jacobian_cell_mm"], 2.0) << out.str();
  EXPECT_EQ(one["solver"]["jacobians"]["coarse"].get<int>(), 0) << out.str();
  EXPECT_NEAR(two["fitted"]["efficiency"].get<double>(), one["fitted"]["efficiency"].get<double>(), 2e-3) << out.str();
  EXPECT_NEAR(two["fitted"]["convection"].get<double>(), one["fitted"]["convection"].get<double>(), 1.0) << out.str();
  EXPECT_LT(two["held_out"]["overall"]["rmse_c"].get<double>(), 1.5) << out.str();
}

// --jacobian-cell auto keeps every Jacobian on the scenario's grid where 1.5 times its spacing would hold the bead's
// width or the plate's thickness in under two cells, and says which.
TEST(ReplayRoundTrip, AutoJacobianGridStaysOnTheScenariosGridWhereTheCoarseOneCannotHoldThePart) {
  FitOptions options = RoundTripFit(cli_test::TempDir("replay_fit_auto_grid"), "fitted.json");
  options.jacobian_cell_mm = kAutoJacobianCell;
  options.max_iterations = 1;  // the grid is chosen before the fit; one iteration shows it
  options.overrides = {"thermal.cell_mm=2.5"};  // 3.75 mm: the 6 mm bead in 1.6 cells
  std::ostringstream out;
  RunFit(options, out);
  EXPECT_NE(out.str().find("Jacobians on the scenario's grid (--jacobian-cell auto: the bead's 6 mm width is under 2 "
                           "cells of 3.75 mm)"),
            std::string::npos)
      << out.str();
  options.overrides = {"thermal.substrate.size_mm=[70, 30, 5]"};  // 3 mm: the plate in 1.7 cells
  RunFit(options, out);
  EXPECT_NE(out.str().find("(--jacobian-cell auto: the plate's 5 mm thickness is under 2 cells of 3 mm)"),
            std::string::npos)
      << out.str();
}

}  // namespace
}  // namespace waam::analysis
