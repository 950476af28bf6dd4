// `waam bench`: every scenario run by `waam run` in its own child process, bench.json and a self-contained report.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace waam::analysis {

// One scenario run of a bench: a scenario file, its result folder's name and its own --set overrides.
struct BenchRun {
  std::filesystem::path file;
  std::string id;                      // result folder <out_dir>/<id>; unique within a bench
  std::vector<std::string> overrides;  // applied after BenchOptions::overrides (a sweep's values)
};

struct BenchOptions {
  // Scenario files or folders (a folder stands for every *.yaml under it, sorted). Empty: "scenarios".
  std::vector<std::filesystem::path> scenarios;
  // When not empty: these runs instead of `scenarios` (a sweep's expanded grid).
  std::vector<BenchRun> runs;
  std::filesystem::path out_dir;       // <out_dir>/<id>/ per scenario, bench.json, report.html
  std::filesystem::path waam_binary;   // the `waam` executable that runs each scenario (`waam run`)
  std::vector<std::string> overrides;  // --set overrides passed to every scenario's run
  std::filesystem::path perf_dir;      // folder of Google Benchmark JSON files to include (empty: <out_dir>/perf)
  bool fresh = false;                  // rerun scenarios whose completed result is already in out_dir
  bool quiet = false;                  // no progress lines on stderr
  int jobs = 1;                        // >= 1: scenarios running at once
  // Budget for the sum of the running scenarios' expected peak memory, GiB (0: 80 % of the physical memory). A
  // scenario's expectation is its peak in the previous result in out_dir, else kFirstMemoryEstimateMb.
  double mem_gb = 0.0;
  int shard_index = 0;                 // run only the runs i with i % shard_count == shard_index
  int shard_count = 1;
  nlohmann::json sweep;                // null, or the sweep's description, stored in bench.json as "sweep"
};

// Expected peak memory of a scenario never run in this output folder, MiB.
inline constexpr double kFirstMemoryEstimateMb = 1024.0;

// Parses "K/N" (0 <= K < N) of --shard into `*index` and `*count`. Throws InputError naming the text.
void ParseShard(const std::string& text, int* index, int* count);

// Runs `waam run <scenario> -o <out_dir>/<id> -q --threads T` for each scenario of the shard in a child process
// (posix_spawn, no shell; stdout and stderr into <out_dir>/<id>/run.log), up to `jobs` at once within the memory
// budget, longest expected first; T = max(1, ThreadCount() / jobs). Measures each child's wall time and peak
// memory (wait4 ru_maxrss), writes <out_dir>/<id>/bench_entry.json atomically, then bench.json (entries in scenario
// order whatever the finishing order) and report.html. A scenario whose bench_entry.json exists for the same
// scenario text and overrides is not rerun (resume after an interrupt) unless `fresh`. Returns the bench.json
// document. Throws InputError for a missing scenario or binary or a bad shard, Interrupted on Ctrl-C (after the
// running children have stopped).
nlohmann::json RunBench(const BenchOptions& options);

// Throws InputError "run <id>: <the loader's message>" for the first run whose scenario loads on its own but not with
// the --set overrides (options.overrides, then the run's: a sweep's values): a value out of its key's limits, say.
// RunBench and the sweeps call it before any run starts; a scenario that is bad on its own is left to its run.
void CheckBenchOverrides(const std::vector<BenchRun>& runs, const BenchOptions& options);

// Merges the bench.json of the shard folders `dirs` (each written by RunBench with a shard, all shards of one bench,
// in any order; or unsharded benches, concatenated in the order given) into <out_dir>/bench.json and report.html,
// the scenarios' folders hard-linked (or copied) into out_dir. The entries come back in the order of one unsharded
// run. Throws InputError for a folder without bench.json, shards of different benches, a missing or repeated
// shard, or a scenario id in two folders.
nlohmann::json MergeBench(const std::vector<std::filesystem::path>& dirs, const std::filesystem::path& out_dir);

// The scenario files named by `paths` (files as given, folders expanded to their *.yaml files, sorted) and the id of
// each (its path relative to the common folder, without .yaml, '/' replaced by '-'). Throws InputError naming a
// path that does not exist or holds no scenario.
std::vector<std::pair<std::filesystem::path, std::string>> BenchScenarios(
    const std::vector<std::filesystem::path>& paths);

// The published figures of models/data/reference_figures.csv with our value for each, from the bench entries
// (bench.json "scenarios") and the fitted model files: [{id, source, quantity, published, published_value, ours,
// unit, scenario}]; `ours` is null when the scenario was not benched.
nlohmann::json ReferenceComparison(const nlohmann::json& scenarios);

// Writes <out_dir>/report.html from the bench.json document and the scenarios' output folders under out_dir:
// one HTML file with embedded images (base64 PNG, inline SVG), no external scripts or styles.
void WriteBenchReport(const nlohmann::json& bench, const std::filesystem::path& out_dir);

}  // namespace waam::analysis
