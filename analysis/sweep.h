// `waam sweep`: a sweep file (a base scenario and a grid or list of --set overrides) expanded into bench runs.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/bench_command.h"

namespace waam::analysis {

// One run of a sweep: its result folder's name and the value (YAML text) of each swept key.
struct SweepRun {
  std::string id;
  std::vector<std::pair<std::string, std::string>> values;  // key path, value as YAML text
};

// A sweep file (docs/BENCHMARKS.md, "Sweeps"), expanded.
struct Sweep {
  std::string name;                  // `name`, default: the file's stem
  std::filesystem::path file;        // the sweep file
  std::filesystem::path base;        // the base scenario (`base`, relative to the sweep file's folder)
  std::vector<std::string> set;      // `set`: "key.path=value" overrides of every run
  std::vector<std::string> keys;     // the swept key paths, in the order of the file
  std::vector<SweepRun> runs;        // a grid: every combination, the last key varying fastest; or the list's order
  std::vector<std::string> metrics;  // "step.metric" columns of the report's table
};

// Most runs a sweep may expand to.
inline constexpr std::size_t kMaxSweepRuns = 100000;

// Parses the text of sweep file `file` (named in messages; `base` is resolved against its folder but not opened).
// Throws InputError "file:line: what is wrong" for YAML that does not parse, a top level that is not a mapping, an
// unknown or missing key, a key path that is not dotted names, a swept key without values, a list run that is not a
// mapping, both or neither of grid and list, more than kMaxSweepRuns runs, or a metric that is not step.metric.
Sweep ParseSweep(const std::string& text, const std::filesystem::path& file);

// Reads and parses the sweep file and checks that its base scenario exists. Throws InputError as ParseSweep does,
// and naming the file for a missing file or base scenario.
Sweep ReadSweep(const std::filesystem::path& file);

// The bench runs of a sweep: the base scenario with each run's values as its overrides.
std::vector<BenchRun> SweepBenchRuns(const Sweep& sweep);

// Runs the sweep as a bench (RunBench with `options`' jobs, shard, memory budget and output folder): the sweep's
// `set` comes before the command line's --set (options.overrides), each run's values after both. Returns
// bench.json, which holds "sweep" (SweepJson) for the report's table. Throws as RunBench does.
nlohmann::json RunSweep(const Sweep& sweep, BenchOptions options);

// The sweep's description stored in bench.json as "sweep": {name, file, base, set, keys, metrics,
// runs [{id, values {key: value}}]}.
nlohmann::json SweepJson(const Sweep& sweep);

}  // namespace waam::analysis
