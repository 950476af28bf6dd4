// `waam bench`: each scenario in a child `waam run` process (isolation, per-scenario peak memory), several at once
// within a memory budget, resumable, one shard of many.
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
#include <functional>
#include <thread>

#include "analysis/scenario.h"
#include "models/core/data_dir.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/core/output_lock.h"
#include "models/core/parallel.h"
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

// Starts `args` (args[0] = binary path) with stdout and stderr into `log`; returns its pid.
pid_t StartChild(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0].c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  WAAM_THROW_UNLESS(rc == 0, "cannot start " << args[0] << ": " << std::strerror(rc));
  return pid;
}

// Whether child `pid` has ended (without blocking); if so, fills its exit code and resource use.
bool ChildDone(pid_t pid, ChildResult* result) {
  int status = 0;
  rusage usage{};
  const pid_t done = wait4(pid, &status, WNOHANG, &usage);
  if (done == 0 || (done < 0 && errno == EINTR)) return false;
  WAAM_DEMAND(done == pid);
  result->exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  result->peak_rss_mb = usage.ru_maxrss / 1024.0;  // KiB on Linux
  result->user_s = usage.ru_utime.tv_sec + usage.ru_utime.tv_usec * 1e-6;
  result->sys_s = usage.ru_stime.tv_sec + usage.ru_stime.tv_usec * 1e-6;
  return true;
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

// One scenario of the bench on its way: its entry so far and, until it is done, the child that runs it.
struct Job {
  BenchRun run;
  fs::path dir;
  nlohmann::json entry;
  bool done = false;               // entry complete (reused, refused input, or the child finished)
  bool reused = false;
  std::vector<std::string> args;   // the child's command line
  double expected_mb = kFirstMemoryEstimateMb;
  double expected_s = -1.0;        // wall time of the previous result (-1: unknown)
  pid_t pid = 0;
  std::chrono::steady_clock::time_point start;
};

// Reuses the completed entry of a run, or records a bad scenario file, or prepares the child's command line.
Job PrepareJob(const BenchRun& run, const BenchOptions& options, int child_threads) {
  Job job;
  job.run = run;
  job.dir = options.out_dir / run.id;
  const fs::path entry_path = job.dir / "bench_entry.json";
  std::vector<std::string> overrides = options.overrides;
  overrides.insert(overrides.end(), run.overrides.begin(), run.overrides.end());
  std::string input = ReadFile(run.file);
  for (const std::string& o : overrides) input += "\n--set " + o;
  const std::string fingerprint = Fingerprint(input);
  std::error_code ec;
  if (fs::is_regular_file(entry_path, ec)) {
    const nlohmann::json old = nlohmann::json::parse(ReadFile(entry_path), nullptr, false);
    if (!old.is_discarded() && !options.fresh && old.value("input_fingerprint", "") == fingerprint) {
      job.entry = old;
      job.done = job.reused = true;
      return job;
    }
    // An older result of this folder is the best guess of the new run's memory and time.
    if (!old.is_discarded() && old.contains("timing") && old["timing"].is_object()) {
      job.expected_mb = old["timing"].value("peak_rss_mb", kFirstMemoryEstimateMb);
      job.expected_s = old["timing"].value("wall_s", -1.0);
    }
  }
  fs::remove(entry_path, ec);

  job.entry = {{"id", run.id}, {"file", run.file.generic_string()}, {"input_fingerprint", fingerprint}};
  if (!run.overrides.empty()) job.entry["overrides"] = run.overrides;
  // The scenario is read here first so that a bad file is reported without starting a child.
  try {
    const Scenario scenario = LoadScenario(run.file, overrides);
    job.entry["scenario"] = scenario.name;
    job.entry["expected_exit_code"] = scenario.run.expected_exit_code;
  } catch (const InputError& e) {
    job.entry["scenario"] = nullptr;
    job.entry["exit_code"] = 2;
    job.entry["expected_exit_code"] = 0;
    job.entry["outcome"] = "fail";
    job.entry["error"] = e.what();
    job.entry["steps"] = nlohmann::json::array();
    job.entry["timing"] = nlohmann::json::object();
    WriteFileAtomic(entry_path, JsonText(job.entry) + "\n");
    job.done = true;
    return job;
  }
  job.args = {options.waam_binary.string(), "run", run.file.string(), "-o", job.dir.string(), "-q",
              "--threads", std::to_string(child_threads)};
  for (const std::string& o : overrides) {
    job.args.push_back("--set");
    job.args.push_back(o);
  }
  return job;
}

// Completes the entry of a job whose child ended and writes its bench_entry.json.
void FinishJob(Job* job, const ChildResult& child) {
  std::error_code ec;
  nlohmann::json summary = nlohmann::json::object();
  if (fs::is_regular_file(job->dir / "summary.json", ec)) {
    summary = nlohmann::json::parse(ReadFile(job->dir / "summary.json"));
  }
  nlohmann::json& entry = job->entry;
  entry["exit_code"] = child.exit_code;
  entry["outcome"] = Outcome(child.exit_code, entry["expected_exit_code"].get<int>());
  entry["steps"] = summary.value("steps", nlohmann::json::array());
  if (child.exit_code != 0 && child.exit_code != 3) entry["error"] = LastLine(job->dir / "run.log");
  entry["timing"] = {{"wall_s", child.wall_s},
                     {"peak_rss_mb", child.peak_rss_mb},
                     {"user_s", child.user_s},
                     {"sys_s", child.sys_s},
                     {"steps", summary.contains("timing") ? summary["timing"]["steps"] : nlohmann::json::object()}};
  WriteFileAtomic(job->dir / "bench_entry.json", JsonText(entry) + "\n");
  job->done = true;
}

// 80 % of the physical memory, GiB.
double DefaultMemoryBudgetGb() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return 8.0;
  return 0.8 * static_cast<double>(pages) * static_cast<double>(page) / (1024.0 * 1024.0 * 1024.0);
}

// Runs the children of the pending jobs, up to `jobs` at once with the sum of their expected peak memory within
// `budget_mb` (a job that alone exceeds it runs when nothing else does). Jobs start longest expected first (unknown
// first of all: a new scenario may be the longest), ties in list order. `report` is called as each job ends.
void RunJobs(std::vector<Job>* all, int jobs, double budget_mb, const std::function<void(Job&)>& report) {
  std::vector<std::size_t> queue;
  for (std::size_t i = 0; i < all->size(); ++i) {
    if (!(*all)[i].done) queue.push_back(i);
  }
  std::stable_sort(queue.begin(), queue.end(), [&](std::size_t a, std::size_t b) {
    const double ta = (*all)[a].expected_s < 0 ? 1e300 : (*all)[a].expected_s;
    const double tb = (*all)[b].expected_s < 0 ? 1e300 : (*all)[b].expected_s;
    return ta > tb;
  });
  std::vector<std::size_t> running;
  double running_mb = 0.0;
  bool interrupted = false;
  bool child_interrupted = false;
  while (!queue.empty() || !running.empty()) {
    if (!interrupted && (InterruptRequested() || child_interrupted)) {
      interrupted = true;
      queue.clear();
      for (std::size_t r : running) kill((*all)[r].pid, SIGINT);  // each removes its partial outputs, exits 130
    }
    // Start what fits.
    for (auto it = queue.begin(); it != queue.end() && static_cast<int>(running.size()) < jobs;) {
      Job& job = (*all)[*it];
      if (!running.empty() && running_mb + job.expected_mb > budget_mb) {
        ++it;
        continue;
      }
      EnsureOutputDirectory(job.dir);
      job.start = std::chrono::steady_clock::now();
      job.pid = StartChild(job.args, job.dir / "run.log");
      running_mb += job.expected_mb;
      running.push_back(*it);
      it = queue.erase(it);
    }
    // Reap what ended.
    bool any = false;
    for (auto it = running.begin(); it != running.end();) {
      Job& job = (*all)[*it];
      ChildResult child;
      if (!ChildDone(job.pid, &child)) {
        ++it;
        continue;
      }
      any = true;
      child.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - job.start).count();
      running_mb -= job.expected_mb;
      it = running.erase(it);
      if (child.exit_code == 130 || interrupted) {
        child_interrupted = true;
        continue;
      }
      FinishJob(&job, child);
      report(job);
    }
    if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (interrupted || child_interrupted) throw Interrupted();
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
  std::vector<fs::path> given = paths;
  if (given.empty()) {
    // No list: ./scenarios (in the repository), else the installed example scenarios (the data folder).
    std::error_code ec;
    const fs::path installed = DataDir() / "scenarios";
    if (fs::is_directory("scenarios", ec)) {
      given.push_back("scenarios");
    } else if (fs::is_directory(installed, ec)) {
      given.push_back(installed);
    } else {
      WAAM_THROW("bench: no scenarios given, and neither ./scenarios nor the example scenarios ("
                 << installed.string() << ") exist: give scenario files or folders, e.g. waam bench my.yaml -o out");
    }
  }
  for (const fs::path& path : given) {
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

void ParseShard(const std::string& text, int* index, int* count) {
  const std::size_t slash = text.find('/');
  bool ok = slash != std::string::npos && slash > 0 && slash + 1 < text.size() &&
            text.find_first_not_of("0123456789/") == std::string::npos && slash < 9 && text.size() - slash < 10;
  if (ok) {
    *index = std::stoi(text.substr(0, slash));
    *count = std::stoi(text.substr(slash + 1));
    ok = *count >= 1 && *index < *count;
  }
  WAAM_THROW_UNLESS(ok, "--shard '" << text << "': expected K/N with 0 <= K < N, e.g. 0/4 for the first of 4 shards");
}

void CheckBenchOverrides(const std::vector<BenchRun>& runs, const BenchOptions& options) {
  for (const BenchRun& run : runs) {
    std::vector<std::string> overrides = options.overrides;
    overrides.insert(overrides.end(), run.overrides.begin(), run.overrides.end());
    if (overrides.empty()) continue;
    try {
      (void)LoadScenario(run.file, overrides);
    } catch (const InputError& e) {
      try {
        (void)LoadScenario(run.file);
      } catch (const InputError&) {
        continue;  // the scenario is bad on its own: its run records that (a bad-input scenario expects exit 2)
      }
      WAAM_THROW("run " << run.id << ": " << e.what());
    }
  }
}

namespace {

// Every run of the bench before sharding: the options' runs, or one per scenario file. Throws InputError for options
// out of range, a missing waam executable or two runs with one result folder.
std::vector<BenchRun> AllRuns(const BenchOptions& options) {
  std::error_code ec;
  WAAM_THROW_UNLESS(fs::is_regular_file(options.waam_binary, ec),
                    "waam executable " << options.waam_binary.string() << " not found");
  WAAM_THROW_UNLESS(options.jobs >= 1, "-j " << options.jobs << ": must be >= 1");
  WAAM_THROW_UNLESS(options.mem_gb >= 0.0, "--mem-gb " << options.mem_gb << ": must be >= 0 (0 = 80 % of memory)");
  WAAM_THROW_UNLESS(options.shard_count >= 1 && options.shard_index >= 0 && options.shard_index < options.shard_count,
                    "shard " << options.shard_index << "/" << options.shard_count << ": must be K/N with 0 <= K < N");
  std::vector<BenchRun> all = options.runs;
  if (all.empty()) {
    for (const auto& [file, id] : BenchScenarios(options.scenarios)) all.push_back({file, id, {}});
  }
  for (std::size_t i = 0; i < all.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      WAAM_THROW_UNLESS(all[i].id != all[j].id, "two runs share the result folder '" << all[i].id << "'");
    }
  }
  return all;
}

// One line on stderr for the `finished`-th of `n` runs to end.
void PrintFinished(const Job& job, std::size_t finished, std::size_t n) {
  const nlohmann::json& entry = job.entry;
  std::fprintf(stderr, "bench [%zu/%zu] %s: %s (exit %d) %.1f s, %.0f MiB peak%s%s%s\n", finished, n,
               job.run.id.c_str(), entry["outcome"].get<std::string>().c_str(), entry["exit_code"].get<int>(),
               entry["timing"].value("wall_s", 0.0), entry["timing"].value("peak_rss_mb", 0.0),
               job.reused ? " (result reused)" : "", entry.contains("error") ? ": " : "",
               entry.contains("error") ? entry["error"].get<std::string>().c_str() : "");
}

// The finished jobs' entries (moved out of `work`) with their counts by outcome, wall time and reused results.
struct BenchEntries {
  nlohmann::json entries = nlohmann::json::array();
  nlohmann::json counts;
  double wall_s = 0.0;
  std::size_t reused = 0;
};

BenchEntries CollectEntries(std::vector<Job>* work) {
  BenchEntries e;
  e.counts = {{"pass", 0}, {"expected_fail", 0}, {"fail", 0}, {"total", work->size()}};
  for (Job& job : *work) {
    const std::string outcome = job.entry["outcome"];
    e.counts[outcome] = e.counts[outcome].get<int>() + 1;
    e.wall_s += job.entry["timing"].value("wall_s", 0.0);
    e.reused += job.reused ? 1 : 0;
    e.entries.push_back(std::move(job.entry));
  }
  return e;
}

}  // namespace

nlohmann::json RunBench(const BenchOptions& options) {
  const std::vector<BenchRun> all = AllRuns(options);
  // The shard: every shard_count-th run, so shards of a sorted folder get a mix of scenarios.
  std::vector<BenchRun> runs;
  for (std::size_t i = options.shard_index; i < all.size(); i += options.shard_count) runs.push_back(all[i]);
  CheckBenchOverrides(runs, options);
  ClaimOutputDirectory(options.out_dir);
  const auto start = std::chrono::steady_clock::now();
  const int jobs = std::max(1, std::min<int>(options.jobs, static_cast<int>(runs.size())));
  const int child_threads = std::max(1, ThreadCount() / jobs);
  const double budget_mb = 1024.0 * (options.mem_gb > 0.0 ? options.mem_gb : DefaultMemoryBudgetGb());

  std::vector<Job> work;
  for (const BenchRun& run : runs) {
    CheckInterrupt();
    work.push_back(PrepareJob(run, options, child_threads));
  }
  const std::size_t n = work.size();
  std::size_t finished = 0;
  auto report = [&](Job& job) {
    ++finished;
    if (!options.quiet) PrintFinished(job, finished, n);
  };
  for (Job& job : work) {
    if (job.done) report(job);
  }
  if (!options.quiet && finished < n) {
    std::fprintf(stderr, "bench: %zu scenario%s to run, %d at once, %d thread%s each, memory budget %.1f GiB\n",
                 n - finished, n - finished == 1 ? "" : "s", jobs, child_threads, child_threads == 1 ? "" : "s",
                 budget_mb / 1024.0);
  }
  RunJobs(&work, jobs, budget_mb, report);

  const BenchEntries e = CollectEntries(&work);
  const fs::path perf_dir = options.perf_dir.empty() ? options.out_dir / "perf" : options.perf_dir;
  nlohmann::json bench = {
      {"scenarios", e.entries},
      {"counts", e.counts},
      {"reference", ReferenceComparison(e.entries)},
      {"timing",
       {{"total_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()},
        {"scenarios_wall_s", e.wall_s},
        {"reused_results", e.reused},
        {"hardware_threads", std::thread::hardware_concurrency()},
        {"jobs", jobs},
        {"threads_per_job", child_threads},
        {"memory_budget_mb", budget_mb},
        {"perf", ReadPerf(perf_dir)}}},
  };
  if (options.shard_count > 1) {
    bench["shard"] = {{"index", options.shard_index}, {"count", options.shard_count}, {"runs_total", all.size()}};
  }
  if (!options.sweep.is_null()) bench["sweep"] = options.sweep;
  WriteFileAtomic(options.out_dir / "bench.json", JsonText(bench) + "\n");
  WriteBenchReport(bench, options.out_dir);
  return bench;
}

}  // namespace waam::analysis
