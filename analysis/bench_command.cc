// `waam bench`: each scenario in a child `waam run` process (isolation, per-scenario peak memory), resumable.
#include "analysis/bench_command.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>

#include "analysis/scenario.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/progress.h"
#include "planner/scenario/scenario.h"

extern char** environ;

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

// FNV-1a 64-bit: a stable fingerprint of a scenario's text and overrides (std::hash is not stable across builds).
std::string Fingerprint(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

struct ChildResult {
  int exit_code = 1;
  double wall_s = 0.0;
  double peak_rss_mb = 0.0;
  double user_s = 0.0;
  double sys_s = 0.0;
};

// Runs `argv` (argv[0] = binary path) with stdout and stderr into `log`; waits for it, forwarding an interrupt.
ChildResult RunChild(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0].c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  WAAM_THROW_UNLESS(rc == 0, "cannot start " << args[0] << ": " << std::strerror(rc));

  int status = 0;
  rusage usage{};
  bool forwarded = false;
  while (true) {
    const pid_t done = wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) WAAM_THROW("waiting for " << args[0] << ": " << std::strerror(errno));
    if (InterruptRequested() && !forwarded) {
      kill(pid, SIGINT);  // the child removes its partial outputs and exits 130
      forwarded = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ChildResult result;
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  result.peak_rss_mb = usage.ru_maxrss / 1024.0;  // KiB on Linux
  result.user_s = usage.ru_utime.tv_sec + usage.ru_utime.tv_usec * 1e-6;
  result.sys_s = usage.ru_stime.tv_sec + usage.ru_stime.tv_usec * 1e-6;
  return result;
}

// The last non-empty line of a log (the child's one-line error), or "".
std::string LastLine(const fs::path& log) {
  std::error_code ec;
  if (!fs::is_regular_file(log, ec)) return "";
  std::string text = ReadFile(log);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  const std::size_t nl = text.find_last_of("\n\r");
  return nl == std::string::npos ? text : text.substr(nl + 1);
}

std::string Outcome(int exit_code, int expected) {
  if (exit_code != expected) return "fail";
  return exit_code == 0 ? "pass" : "expected_fail";
}

// Runs one scenario (or reuses its completed entry) and returns its bench entry.
nlohmann::json BenchOne(const fs::path& file, const std::string& id, const BenchOptions& options,
                        bool* reused) {
  const fs::path dir = options.out_dir / id;
  const fs::path entry_path = dir / "bench_entry.json";
  std::string input = ReadFile(file);
  for (const std::string& o : options.overrides) input += "\n--set " + o;
  const std::string fingerprint = Fingerprint(input);
  std::error_code ec;
  if (!options.fresh && fs::is_regular_file(entry_path, ec)) {
    nlohmann::json old = nlohmann::json::parse(ReadFile(entry_path), nullptr, false);
    if (!old.is_discarded() && old.value("input_fingerprint", "") == fingerprint) {
      *reused = true;
      return old;
    }
  }
  *reused = false;
  fs::remove(entry_path, ec);

  nlohmann::json entry = {{"id", id}, {"file", file.generic_string()}, {"input_fingerprint", fingerprint}};
  // The scenario is read here first so that a bad file is reported without starting a child.
  int expected = 0;
  try {
    const Scenario scenario = LoadScenario(file, options.overrides);
    entry["scenario"] = scenario.name;
    expected = scenario.run.expected_exit_code;
  } catch (const InputError& e) {
    entry["scenario"] = nullptr;
    entry["exit_code"] = 2;
    entry["expected_exit_code"] = 0;
    entry["outcome"] = "fail";
    entry["error"] = e.what();
    entry["steps"] = nlohmann::json::array();
    entry["timing"] = nlohmann::json::object();
    WriteFileAtomic(entry_path, entry.dump(2) + "\n");
    return entry;
  }
  EnsureOutputDirectory(dir);
  std::vector<std::string> args = {options.waam_binary.string(), "run", file.string(), "-o", dir.string(), "-q"};
  for (const std::string& o : options.overrides) {
    args.push_back("--set");
    args.push_back(o);
  }
  const ChildResult child = RunChild(args, dir / "run.log");
  if (child.exit_code == 130 || InterruptRequested()) throw Interrupted();

  nlohmann::json summary = nlohmann::json::object();
  if (fs::is_regular_file(dir / "summary.json", ec)) summary = nlohmann::json::parse(ReadFile(dir / "summary.json"));
  entry["exit_code"] = child.exit_code;
  entry["expected_exit_code"] = expected;
  entry["outcome"] = Outcome(child.exit_code, expected);
  entry["steps"] = summary.value("steps", nlohmann::json::array());
  if (child.exit_code != 0 && child.exit_code != 3) entry["error"] = LastLine(dir / "run.log");
  entry["timing"] = {{"wall_s", child.wall_s},
                     {"peak_rss_mb", child.peak_rss_mb},
                     {"user_s", child.user_s},
                     {"sys_s", child.sys_s},
                     {"steps", summary.contains("timing") ? summary["timing"]["steps"] : nlohmann::json::object()}};
  WriteFileAtomic(entry_path, entry.dump(2) + "\n");
  return entry;
}

// Google Benchmark JSON files of `dir` (tools/perf_bench.sh) as [{file, name, real_time, cpu_time, time_unit,
// iterations, counters}].
nlohmann::json ReadPerf(const fs::path& dir) {
  nlohmann::json perf = nlohmann::json::array();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return perf;
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    if (e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  static const std::vector<std::string> kStandard = {
      "name", "run_name", "run_type", "repetitions", "repetition_index", "threads", "iterations", "real_time",
      "cpu_time", "time_unit", "family_index", "per_family_instance_index", "aggregate_name", "label"};
  for (const fs::path& file : files) {
    const nlohmann::json doc = nlohmann::json::parse(ReadFile(file), nullptr, false);
    if (doc.is_discarded() || !doc.contains("benchmarks")) continue;
    for (const nlohmann::json& b : doc["benchmarks"]) {
      nlohmann::json counters = nlohmann::json::object();
      for (auto it = b.begin(); it != b.end(); ++it) {
        if (it.value().is_number() &&
            std::find(kStandard.begin(), kStandard.end(), it.key()) == kStandard.end()) {
          counters[it.key()] = it.value();
        }
      }
      perf.push_back({{"file", file.filename().string()},
                      {"name", b.value("name", "")},
                      {"real_time", b.value("real_time", 0.0)},
                      {"cpu_time", b.value("cpu_time", 0.0)},
                      {"time_unit", b.value("time_unit", "")},
                      {"iterations", b.value("iterations", 0)},
                      {"counters", counters}});
    }
  }
  return perf;
}

}  // namespace

std::vector<std::pair<fs::path, std::string>> BenchScenarios(const std::vector<fs::path>& paths) {
  std::vector<fs::path> files;
  std::vector<fs::path> roots;
  for (const fs::path& path : paths.empty() ? std::vector<fs::path>{"scenarios"} : paths) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
      std::vector<fs::path> found;
      for (const fs::directory_entry& e : fs::recursive_directory_iterator(path)) {
        if (e.is_regular_file() && e.path().extension() == ".yaml") found.push_back(e.path());
      }
      WAAM_THROW_UNLESS(!found.empty(), path.string() << ": folder holds no scenario (*.yaml)");
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
      roots.insert(roots.end(), found.size(), path);
    } else {
      WAAM_THROW_UNLESS(fs::is_regular_file(path, ec), path.string() << ": scenario file not found");
      files.push_back(path);
      roots.push_back(path.parent_path());
    }
  }
  std::vector<std::pair<fs::path, std::string>> scenarios;
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::string id = files[i].lexically_relative(roots[i]).replace_extension().generic_string();
    if (id.empty() || id.rfind("..", 0) == 0) id = files[i].stem().string();
    std::replace(id.begin(), id.end(), '/', '-');
    for (const auto& [other_file, other_id] : scenarios) {
      WAAM_THROW_UNLESS(other_id != id, files[i].string() << " and " << other_file.string()
                                                          << " would share the result folder '" << id
                                                          << "'; bench them separately");
    }
    scenarios.emplace_back(files[i], id);
  }
  return scenarios;
}

nlohmann::json RunBench(const BenchOptions& options) {
  std::error_code ec;
  WAAM_THROW_UNLESS(fs::is_regular_file(options.waam_binary, ec),
                    "waam executable " << options.waam_binary.string() << " not found");
  const auto scenarios = BenchScenarios(options.scenarios);
  EnsureOutputDirectory(options.out_dir);
  const auto start = std::chrono::steady_clock::now();

  nlohmann::json entries = nlohmann::json::array();
  nlohmann::json counts = {{"pass", 0}, {"expected_fail", 0}, {"fail", 0}, {"total", scenarios.size()}};
  double entries_wall_s = 0.0;
  std::size_t reused_count = 0;
  for (std::size_t i = 0; i < scenarios.size(); ++i) {
    const auto& [file, id] = scenarios[i];
    CheckInterrupt();
    if (!options.quiet) std::fprintf(stderr, "bench [%zu/%zu] %s ...\n", i + 1, scenarios.size(), id.c_str());
    bool reused = false;
    nlohmann::json entry = BenchOne(file, id, options, &reused);
    const std::string outcome = entry["outcome"];
    counts[outcome] = counts[outcome].get<int>() + 1;
    const double wall = entry["timing"].value("wall_s", 0.0);
    entries_wall_s += wall;
    reused_count += reused ? 1 : 0;
    if (!options.quiet) {
      std::fprintf(stderr, "bench [%zu/%zu] %s: %s (exit %d) %.1f s, %.0f MiB peak%s%s%s\n", i + 1,
                   scenarios.size(), id.c_str(), outcome.c_str(), entry["exit_code"].get<int>(), wall,
                   entry["timing"].value("peak_rss_mb", 0.0), reused ? " (result reused)" : "",
                   entry.contains("error") ? ": " : "",
                   entry.contains("error") ? entry["error"].get<std::string>().c_str() : "");
    }
    entries.push_back(std::move(entry));
  }
  const fs::path perf_dir = options.perf_dir.empty() ? options.out_dir / "perf" : options.perf_dir;
  nlohmann::json bench = {
      {"scenarios", entries},
      {"counts", counts},
      {"reference", ReferenceComparison(entries)},
      {"timing",
       {{"total_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()},
        {"scenarios_wall_s", entries_wall_s},
        {"reused_results", reused_count},
        {"hardware_threads", std::thread::hardware_concurrency()},
        {"perf", ReadPerf(perf_dir)}}},
  };
  WriteFileAtomic(options.out_dir / "bench.json", bench.dump(2) + "\n");
  WriteBenchReport(bench, options.out_dir);
  return bench;
}

}  // namespace waam::analysis
