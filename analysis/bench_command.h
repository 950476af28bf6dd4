// `waam bench`: every scenario run by `waam run` in its own child process, bench.json and a self-contained report.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace waam::analysis {

struct BenchOptions {
  // Scenario files or folders (a folder stands for every *.yaml under it, sorted). Empty: "scenarios".
  std::vector<std::filesystem::path> scenarios;
  std::filesystem::path out_dir;       // <out_dir>/<id>/ per scenario, bench.json, report.html
  std::filesystem::path waam_binary;   // the `waam` executable that runs each scenario (`waam run`)
  std::vector<std::string> overrides;  // --set overrides passed to every scenario's run
  std::filesystem::path perf_dir;      // folder of Google Benchmark JSON files to include (empty: <out_dir>/perf)
  bool fresh = false;                  // rerun scenarios whose completed result is already in out_dir
  bool quiet = false;                  // no progress lines on stderr
};

// Runs `waam run <scenario> -o <out_dir>/<id> -q` for each scenario in a child process (posix_spawn, no shell;
// stdout and stderr into <out_dir>/<id>/run.log), measures its wall time and peak memory (wait4 ru_maxrss), writes
// <out_dir>/<id>/bench_entry.json atomically, then bench.json and report.html. A scenario whose bench_entry.json
// exists for the same scenario text and overrides is not rerun (resume after an interrupt) unless `fresh`.
// Returns the bench.json document. Throws InputError for a missing scenario or binary, Interrupted on Ctrl-C.
nlohmann::json RunBench(const BenchOptions& options);

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
