// `waam bench -j`, --shard and --merge, and `waam sweep`: the same results whatever runs at once or where, the
// sweep file reader's expansion and its bad inputs.
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/bench_command.h"
#include "analysis/sweep.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using cli_test::ReadJson;

// Three tiny scenarios (two-layer blocks, 1 mm voxels), each well under a second of compute; one is checked on the
// cell too.
fs::path TinyScenarios(const std::string& name) {
  const fs::path dir = cli_test::TempDir(name);
  const std::string block = R"(part:
  generator: {type: box, size_mm: [30, 20, 3]}
slicing:
  type: planar
  layer_height_mm: 1.5
process:
  travel_speed_mm_min: 400
  wire_feed_mm_min: 3200
simulation:
  voxel_mm: 1.0
)";
  std::ofstream(dir / "a_continuous.yaml") << "name: a_continuous\n" << block
                                           << "path: {pattern: continuous, bead_width_mm: 6}\n"
                                              "run: {steps: [plan, simulate]}\n";
  std::ofstream(dir / "b_hybrid.yaml") << "name: b_hybrid\n" << block
                                       << "path: {pattern: hybrid, bead_width_mm: 5}\n"
                                          "run: {steps: [plan, check, simulate]}\n";
  std::ofstream(dir / "c_contour.yaml") << "name: c_contour\n" << block
                                        << "path: {pattern: contour, bead_width_mm: 7}\n"
                                           "run: {steps: [plan, simulate]}\n";
  return dir;
}

BenchOptions Options(const fs::path& scenarios, const std::string& out) {
  BenchOptions options;
  options.scenarios = {scenarios};
  options.out_dir = cli_test::TempDir(out);
  options.waam_binary = WAAM_BINARY;
  options.quiet = true;
  return options;
}

// A bench document without what depends on the machine and the schedule: timings and the merge's sources.
nlohmann::json WithoutTimings(nlohmann::json bench) {
  bench.erase("timing");
  bench.erase("merged_from");
  for (nlohmann::json& e : bench["scenarios"]) e.erase("timing");
  return bench;
}

TEST(BenchParallel, TwoJobsGiveTheSameBenchAsOne) {
  const fs::path scenarios = TinyScenarios("bench_j_scenarios");
  BenchOptions one = Options(scenarios, "bench_j1");
  BenchOptions two = Options(scenarios, "bench_j2");
  two.jobs = 2;
  const nlohmann::json a = RunBench(one);
  const nlohmann::json b = RunBench(two);
  ASSERT_EQ(a["scenarios"].size(), 3u);
  EXPECT_EQ(a["counts"]["pass"].get<int>(), 3) << a["counts"].dump();
  EXPECT_EQ(b["timing"]["jobs"].get<int>(), 2);
  EXPECT_GE(b["timing"]["threads_per_job"].get<int>(), 1);
  EXPECT_EQ(WithoutTimings(a).dump(1), WithoutTimings(b).dump(1)) << "-j 2 must give the bench of -j 1";
  EXPECT_EQ(WithoutTimings(ReadJson(two.out_dir / "bench.json")).dump(), WithoutTimings(b).dump());
  // Each run's own outputs are the same too.
  for (const char* id : {"a_continuous", "b_hybrid", "c_contour"}) {
    EXPECT_EQ(ReadFile(one.out_dir / id / "plan" / "plan.json"), ReadFile(two.out_dir / id / "plan" / "plan.json"))
        << id;
  }
}

TEST(BenchParallel, ShardsRunAtOnceThenMergedMatchOneRun) {
  const fs::path scenarios = TinyScenarios("bench_shard_scenarios");
  const nlohmann::json whole = RunBench(Options(scenarios, "bench_whole"));
  const fs::path s0 = cli_test::TempDir("bench_shard0"), s1 = cli_test::TempDir("bench_shard1"),
                 merged = cli_test::TempDir("bench_merged");
  // Both shards at once, as two jobs of a cluster array would run them.
  const std::string bench = std::string(WAAM_BINARY) + " bench " + scenarios.string() + " -q --threads 1";
  const std::string both = "(" + bench + " --shard 0/2 -o " + s0.string() + " >/dev/null & " + bench +
                           " --shard 1/2 -o " + s1.string() + " >/dev/null & wait)";
  ASSERT_EQ(std::system(both.c_str()), 0);
  const nlohmann::json b0 = ReadJson(s0 / "bench.json"), b1 = ReadJson(s1 / "bench.json");
  ASSERT_EQ(b0["scenarios"].size(), 2u) << "shard 0/2 of 3 runs scenarios 0 and 2";
  ASSERT_EQ(b1["scenarios"].size(), 1u);
  EXPECT_EQ(b0["shard"]["index"].get<int>(), 0);
  EXPECT_EQ(b1["shard"]["runs_total"].get<int>(), 3);

  std::string err;
  // Given in the other order: the merge restores the order of one run.
  ASSERT_EQ(cli_test::RunWaam("bench --merge " + s1.string() + " " + s0.string() + " -o " + merged.string(), &err), 0)
      << err;
  const nlohmann::json m = ReadJson(merged / "bench.json");
  EXPECT_EQ(WithoutTimings(m).dump(1), WithoutTimings(whole).dump(1))
      << "the merged shards must give the outcomes and metrics of one run";
  EXPECT_TRUE(fs::exists(merged / "b_hybrid" / "summary.json")) << "the scenarios' folders come along";
  const std::string report = ReadFile(merged / "report.html");
  EXPECT_NE(report.find("scenario b_hybrid"), std::string::npos);
  EXPECT_NE(report.find("data:image/png;base64,"), std::string::npos) << "pictures from the shards' folders";

  // A missing or repeated shard is refused, naming it.
  EXPECT_EQ(cli_test::RunWaam("bench --merge " + s0.string() + " -o " + cli_test::TempDir("m1").string(), &err), 2);
  EXPECT_THAT(err, HasSubstr("shard 1/2 missing"));
  EXPECT_EQ(cli_test::RunWaam("bench --merge " + s0.string() + " " + s0.string() + " -o " +
                                  cli_test::TempDir("m2").string(), &err), 2);
  EXPECT_THAT(err, HasSubstr("shard 0/2 given twice"));
  EXPECT_EQ(cli_test::RunWaam("bench " + scenarios.string() + " --shard 2/2 -o " + cli_test::TempDir("m3").string(),
                              &err), 2);
  EXPECT_THAT(err, HasSubstr("--shard '2/2': expected K/N with 0 <= K < N"));
}

TEST(BenchParallel, MemoryBudgetStillRunsEveryScenario) {
  // A budget below one scenario's first estimate: they run one at a time, each alone, and all complete.
  BenchOptions options = Options(TinyScenarios("bench_mem_scenarios"), "bench_mem");
  options.jobs = 3;
  options.mem_gb = 0.1;
  const nlohmann::json bench = RunBench(options);
  EXPECT_EQ(bench["counts"]["pass"].get<int>(), 3);
  EXPECT_DOUBLE_EQ(bench["timing"]["memory_budget_mb"].get<double>(), 0.1 * 1024.0);
}

constexpr char kGridSweep[] = R"(# a grid
base: tiny.yaml
name: width_by_pattern
set: {simulation.voxel_mm: 1}
grid:
  path.pattern: [hybrid, continuous]
  path.bead_width_mm: [5, 6, 7]
metrics: [plan.layers, simulate.volume_error_pct]
)";

TEST(Sweep, GridExpandsToEveryCombinationLastKeyFastest) {
  const Sweep sweep = ParseSweep(kGridSweep, "/data/sweeps/grid.yaml");
  EXPECT_EQ(sweep.name, "width_by_pattern");
  EXPECT_EQ(sweep.base, fs::path("/data/sweeps/tiny.yaml"));
  EXPECT_THAT(sweep.set, ::testing::ElementsAre("simulation.voxel_mm=1"));
  EXPECT_THAT(sweep.keys, ::testing::ElementsAre("path.pattern", "path.bead_width_mm"));
  ASSERT_EQ(sweep.runs.size(), 6u) << "2 x 3";
  EXPECT_EQ(sweep.runs[0].id, "000-hybrid-5");
  EXPECT_EQ(sweep.runs[2].id, "002-hybrid-7");
  EXPECT_EQ(sweep.runs[3].id, "003-continuous-5");
  const std::vector<BenchRun> runs = SweepBenchRuns(sweep);
  EXPECT_THAT(runs[4].overrides, ::testing::ElementsAre("path.pattern=continuous", "path.bead_width_mm=6"));
  std::set<std::string> ids;
  for (const SweepRun& r : sweep.runs) ids.insert(r.id);
  EXPECT_EQ(ids.size(), sweep.runs.size()) << "ids are unique";
}

TEST(Sweep, ListRunsKeepTheirOrderAndListValuesStayLists) {
  const Sweep sweep = ParseSweep("base: b.yaml\nlist:\n  - {path.pattern: hybrid}\n"
                                 "  - {path.pattern: contour, part.generator.size_mm: [30, 20, 3]}\n",
                                 "s.yaml");
  ASSERT_EQ(sweep.runs.size(), 2u);
  EXPECT_THAT(sweep.keys, ::testing::ElementsAre("path.pattern", "part.generator.size_mm"));
  EXPECT_EQ(sweep.runs[1].values[1].second, "[30, 20, 3]");
  EXPECT_EQ(sweep.metrics.size(), 5u) << "the default metrics";
}

TEST(Sweep, MalformedFilesNameFileAndLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"base: b.yaml\ngrid: {path.pattern: [a\n", "s.yaml:3: YAML syntax error"},
      {"- 1\n", "s.yaml:1: a sweep file is a mapping"},
      {"grid: {path.pattern: [a]}\n", "s.yaml:1: base: missing"},
      {"base: b.yaml\n", "exactly one of grid and list"},
      {"base: b.yaml\ngrid: {path.pattern: [a]}\nlist: [{path.pattern: b}]\n", "exactly one of grid and list"},
      {"base: b.yaml\ngrid:\n  path.pattern: []\n", "s.yaml:3: grid: path.pattern: must be a non-empty list"},
      {"base: b.yaml\ngrid:\n  path.pattern: hybrid\n", "s.yaml:3: grid: path.pattern: must be a non-empty list"},
      {"base: b.yaml\ngrid:\n  path=pattern: [a]\n", "s.yaml:3: grid: key 'path=pattern' is not a setting's key"},
      {"base: b.yaml\nlist:\n  - [1, 2]\n", "s.yaml:3: list: each run must be a mapping"},
      {"base: b.yaml\ngrid: {a.b: [{c: 1}]}\n", "s.yaml:2: a.b: a value must be a number, a name or a list"},
      {"base: b.yaml\ngrid: {a.b: [1]}\nmetrics: [layers]\n", "s.yaml:3: metrics: 'layers' is not step.metric"},
      {"base: b.yaml\ngrid: {a.b: [1]}\nseed: 3\n", "s.yaml:3: unknown key 'seed'"},
      {"base: b.yaml\ngrid:\n  a.b: [0,1,2,3,4,5,6,7,8,9]\n  c.d: [0,1,2,3,4,5,6,7,8,9]\n  e.f: [0,1,2,3,4,5,6,7,8,9]\n"
       "  g.h: [0,1,2,3,4,5,6,7,8,9]\n  i.j: [0,1,2,3,4,5,6,7,8,9]\n  k.l: [0,1,2,3,4,5,6,7,8,9]\n",
       "s.yaml:2: grid: more than 100000 runs"},
  };
  for (const auto& [text, message] : cases) {
    try {
      ParseSweep(text, "s.yaml");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(message)) << text;
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line";
    }
  }
}

TEST(Sweep, RunsAsABenchWithATableOfMetricsAgainstValues) {
  const fs::path dir = cli_test::TempDir("sweep_files");
  std::ofstream(dir / "tiny.yaml") << "name: tiny\npart:\n  generator: {type: box, size_mm: [30, 20, 3]}\n"
                                      "slicing: {type: planar, layer_height_mm: 1.5}\n"
                                      "path: {pattern: continuous, bead_width_mm: 6}\n"
                                      "process: {travel_speed_mm_min: 400, wire_feed_mm_min: 3200}\n"
                                      "simulation: {voxel_mm: 2}\nrun: {steps: [plan, simulate]}\n";
  std::ofstream(dir / "widths.yaml") << "base: tiny.yaml\nset: {simulation.voxel_mm: 1}\n"
                                        "grid:\n  path.bead_width_mm: [5, 7]\nmetrics: [plan.weld_length_mm]\n";
  const fs::path out = cli_test::TempDir("sweep_out");
  std::string err;
  ASSERT_EQ(cli_test::RunWaam("sweep " + (dir / "widths.yaml").string() + " -o " + out.string() + " -j 2 -q", &err), 0)
      << err;
  const nlohmann::json bench = ReadJson(out / "bench.json");
  ASSERT_EQ(bench["scenarios"].size(), 2u);
  EXPECT_EQ(bench["scenarios"][0]["id"], "000-5");
  EXPECT_EQ(bench["sweep"]["runs"][1]["values"]["path.bead_width_mm"], "7");
  // The swept value reached the run: a wider bead needs less weld length on the same block.
  auto weld = [&](int i) {
    for (const nlohmann::json& s : bench["scenarios"][i]["steps"]) {
      if (s["name"] == "plan") return s["metrics"]["weld_length_mm"].get<double>();
    }
    return -1.0;
  };
  EXPECT_GT(weld(0), weld(1)) << "5 mm beads weld longer than 7 mm beads";
  const std::string report = ReadFile(out / "report.html");
  EXPECT_NE(report.find("<h2>Sweep</h2>"), std::string::npos);
  EXPECT_NE(report.find("<th>path.bead_width_mm</th>"), std::string::npos);
  EXPECT_NE(report.find("<th>plan.weld_length_mm</th>"), std::string::npos);

  // A malformed sweep: one line naming file:line, exit 2, nothing written.
  std::ofstream(dir / "bad.yaml") << "base: tiny.yaml\ngrid:\n  path.bead_width_mm: 5\n";
  const fs::path bad_out = cli_test::TempDir("sweep_bad_out") / "x";
  EXPECT_EQ(cli_test::RunWaam("sweep " + (dir / "bad.yaml").string() + " -o " + bad_out.string(), &err), 2);
  EXPECT_THAT(err, HasSubstr((dir / "bad.yaml").string() + ":3: grid: path.bead_width_mm"));
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(fs::exists(bad_out));
}

}  // namespace
}  // namespace waam::analysis
