// `waam bench [scenarios...] -o <dir>`: command-line options of the scenario benchmark.
#include <unistd.h>

#include <cstdio>
#include <memory>

#include "analysis/bench_command.h"
#include "app/commands.h"
#include "models/core/error.h"

namespace waam::app {

void AddBenchCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::BenchOptions>();
  auto shard = std::make_shared<std::string>();
  auto merge = std::make_shared<std::vector<std::filesystem::path>>();
  CLI::App* command = app.add_subcommand(
      "bench",
      "Benchmark scenarios reproducibly: each scenario runs as `waam run` in its own child process (plan, check,\n"
      "simulate and the scenario's optional steps), with its wall time and peak memory; -j N runs N at once\n"
      "(each child gets --threads = threads / N, at least 1) while the sum of their expected peak memory (the\n"
      "previous result's in the output directory, else 1 GiB) stays within --mem-gb. --shard K/N runs every N-th\n"
      "scenario from the K-th (K = 0..N-1), for a cluster; --merge DIR... -o DIR puts the shards back together.\n"
      "Arguments are scenario files or folders (every *.yaml under a folder); default: ./scenarios, else the\n"
      "installed example scenarios (<data>/scenarios, see waam --version). Scenarios with\n"
      "`run: {expected_exit_code: 3}` (the planted cell faults) count as expected_fail when check finds the fault.\n"
      "Writes to the output directory:\n"
      "  <id>/                 the scenario's `waam run` outputs (summary.json, plan/, check/, simulate/), run.log\n"
      "                        (its stdout and stderr) and bench_entry.json (written last: the completed result)\n"
      "  bench.json            scenarios [{id, file, scenario, exit_code, expected_exit_code, outcome (pass |\n"
      "                        expected_fail | fail), steps [{name, status, exit_code, outputs, metrics}], error,\n"
      "                        timing {wall_s, peak_rss_mb, user_s, sys_s, steps}}], counts, reference (the papers'\n"
      "                        figures next to ours), timing {total_s, scenarios_wall_s, reused_results, jobs,\n"
      "                        threads_per_job, memory_budget_mb, perf}, shard {index, count, runs_total} (with\n"
      "                        --shard), sweep (waam sweep), merged_from (--merge)\n"
      "  report.html           one self-contained page: tables, published figures, model and void plots, pictures\n"
      "An interrupted bench resumes: scenarios whose bench_entry.json matches the scenario text are not rerun\n"
      "(--fresh reruns all). Inner-loop benchmarks: tools/perf_bench.sh <dir>/perf writes Google Benchmark JSON that\n"
      "the report includes. Exit code 3 when a scenario did not end with its expected exit code.");
  command->add_option("scenarios", options->scenarios, "Scenario files or folders (default: ./scenarios, else the installed examples)");
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing)")->required();
  command->add_option("--set", options->overrides,
                      "Override a setting in every scenario, key.path=value (repeatable), e.g. "
                      "--set simulation.voxel_mm=1");
  command->add_option("--perf", options->perf_dir,
                      "Folder of Google Benchmark JSON files for the report (default: <out>/perf)");
  command->add_flag("--fresh", options->fresh, "Rerun every scenario even if its completed result is there");
  command->add_option("-j,--jobs", options->jobs, "Scenarios run at once (default 1)")->check(CLI::Range(1, 4096));
  command->add_option("--mem-gb", options->mem_gb,
                      "Budget for the running scenarios' expected peak memory, GiB (default 0 = 80 % of memory)")
      ->check(CLI::Range(0.0, 1e6));
  command->add_option("--shard", *shard, "Run only shard K of N (K/N, 0 <= K < N): scenarios K, K+N, K+2N, ...");
  command->add_option("--merge", *merge,
                      "Merge the bench folders of all shards (or of separate benches) into -o instead of running")
      ->expected(1, -1);
  command->add_flag("-q,--quiet", options->quiet, "No progress lines on stderr");
  command->callback([options, shard, merge, runner] {
    *runner = [options, shard, merge] {
      WAAM_THROW_UNLESS(merge->empty() || (options->scenarios.empty() && shard->empty()),
                        "--merge takes bench folders, not scenarios or --shard");
      if (!shard->empty()) analysis::ParseShard(*shard, &options->shard_index, &options->shard_count);
      char self[4096];
      const ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
      if (n > 0) options->waam_binary = std::string(self, static_cast<std::size_t>(n));
      const nlohmann::json bench = merge->empty() ? analysis::RunBench(*options)
                                                  : analysis::MergeBench(*merge, options->out_dir);
      const nlohmann::json& c = bench["counts"];
      const nlohmann::json& t = bench["timing"];
      std::printf("%d scenarios: %d pass, %d expected fail, %d fail; %.1f s of scenario runs (%d results reused), "
                  "%.1f s now -> %s\n",
                  c["total"].get<int>(), c["pass"].get<int>(), c["expected_fail"].get<int>(), c["fail"].get<int>(),
                  t["scenarios_wall_s"].get<double>(), t["reused_results"].get<int>(), t["total_s"].get<double>(),
                  (options->out_dir / "report.html").string().c_str());
      return c["fail"].get<int>() == 0 ? kExitOk : kExitViolations;
    };
  });
}

}  // namespace waam::app
