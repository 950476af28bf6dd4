// `waam sweep <sweep.yaml> -o <dir>`: a base scenario over a grid or list of settings, run as a bench.
#include <unistd.h>

#include <cstdio>
#include <memory>

#include "analysis/sweep.h"
#include "analysis/sweep_dask.h"
#include "app/commands.h"

namespace waam::app {

void AddSweepCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::BenchOptions>();
  auto file = std::make_shared<std::filesystem::path>();
  auto shard = std::make_shared<std::string>();
  auto dask = std::make_shared<std::string>();
  CLI::App* command = app.add_subcommand(
      "sweep",
      "Run a base scenario over a grid or a list of settings, as `waam bench` runs scenarios (each run a child\n"
      "`waam run`, -j, --mem-gb, --shard, resume). The sweep file (docs/BENCHMARKS.md, Sweeps):\n"
      "  base: box.yaml                       # the scenario, relative to the sweep file\n"
      "  set: {simulation.voxel_mm: 1}        # optional: --set of every run\n"
      "  grid:                                # every combination (or list: [{key: value, ...}, ...])\n"
      "    path.pattern: [hybrid, continuous]\n"
      "    path.bead_width_mm: [5, 6, 7]\n"
      "  metrics: [plan.layers, simulate.deviation/rms_mm]   # optional: the table's step.metric columns\n"
      "Writes what `waam bench` writes (run folders <index>-<values>/, bench.json with \"sweep\", report.html with\n"
      "the table of the metrics against the swept values). Shards merge with `waam bench --merge`. Exit code 3\n"
      "when a run did not end with its expected exit code. --dask ADDRESS runs each run as a task of a\n"
      "dask.distributed cluster (docs/CLUSTER.md) and merges the results into -o.");
  command->add_option("sweep", *file, "Sweep file (YAML)")->required();
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing)")->required();
  command->add_option("--set", options->overrides,
                      "Override a setting in every run, key.path=value (repeatable; the swept keys win)");
  command->add_flag("--fresh", options->fresh, "Rerun every run even if its completed result is there");
  command->add_option("-j,--jobs", options->jobs, "Runs at once (default 1)")->check(CLI::Range(1, 4096));
  command->add_option("--mem-gb", options->mem_gb,
                      "Budget for the running runs' expected peak memory, GiB (default 0 = 80 % of memory)")
      ->check(CLI::Range(0.0, 1e6));
  command->add_option("--shard", *shard, "Run only shard K of N (K/N, 0 <= K < N): runs K, K+N, K+2N, ...");
  command->add_option("--dask", *dask,
                      "Run on the dask.distributed cluster whose scheduler is at this address (tcp://host:port): "
                      "one task per run, results merged into -o");
  command->add_flag("-q,--quiet", options->quiet, "No progress lines on stderr");
  command->callback([options, file, shard, dask, runner] {
    *runner = [options, file, shard, dask] {
      const analysis::Sweep sweep = analysis::ReadSweep(*file);
      if (!shard->empty()) analysis::ParseShard(*shard, &options->shard_index, &options->shard_count);
      char self[4096];
      const ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
      if (n > 0) options->waam_binary = std::string(self, static_cast<std::size_t>(n));
      const nlohmann::json bench =
          dask->empty() ? analysis::RunSweep(sweep, *options) : analysis::RunSweepOnDask(sweep, *options, *dask);
      const nlohmann::json& c = bench["counts"];
      std::printf("sweep %s: %d runs: %d pass, %d expected fail, %d fail; %.1f s now -> %s\n", sweep.name.c_str(),
                  c["total"].get<int>(), c["pass"].get<int>(), c["expected_fail"].get<int>(), c["fail"].get<int>(),
                  bench["timing"]["total_s"].get<double>(), (options->out_dir / "report.html").string().c_str());
      return c["fail"].get<int>() == 0 ? kExitOk : kExitViolations;
    };
  });
}

}  // namespace waam::app
