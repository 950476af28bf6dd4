// The Dask driver of `waam sweep --dask`: starts analysis/data/dask/dask_sweep.py, then merges the shards it brings.
#include "analysis/sweep_dask.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "models/core/data_dir.h"
#include "models/core/error.h"
#include "models/core/files.h"

extern char** environ;

namespace waam::analysis {
namespace {

namespace fs = std::filesystem;

// Runs `args` (args[0] a path) with this process's stdout and stderr and waits for it; returns its exit code.
int RunAndWait(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0].c_str(), nullptr, nullptr, argv.data(), environ);
  WAAM_THROW_UNLESS(rc == 0, "cannot start " << args[0] << ": " << std::strerror(rc)
                                             << " (the Dask driver needs Debian's python3 and python3-distributed)");
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    WAAM_DEMAND(errno == EINTR);
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

}  // namespace

nlohmann::json RunSweepOnDask(const Sweep& sweep, const BenchOptions& options, const std::string& scheduler) {
  WAAM_THROW_UNLESS(!scheduler.empty(), "--dask: give the scheduler's address, e.g. tcp://127.0.0.1:8786");
  WAAM_THROW_UNLESS(options.shard_count <= 1, "--dask runs every run of the sweep: leave out --shard");
  WAAM_THROW_UNLESS(!sweep.runs.empty(), sweep.file.string() << ": the sweep has no runs");
  BenchOptions checked = options;
  checked.overrides = sweep.set;
  checked.overrides.insert(checked.overrides.end(), options.overrides.begin(), options.overrides.end());
  CheckBenchOverrides(SweepBenchRuns(sweep), checked);
  const char* python_env = std::getenv("WAAM_PYTHON");
  const std::string python = python_env != nullptr && *python_env != '\0' ? python_env : "/usr/bin/python3";
  const fs::path driver = DataDir() / "analysis" / "data" / "dask" / "dask_sweep.py";
  WAAM_THROW_UNLESS(fs::is_regular_file(driver), driver.string() << ": the Dask driver is missing from the data");
  const std::size_t shards = sweep.runs.size();
  const fs::path shard_root = options.out_dir / "dask_shards";  // the driver makes it once the scheduler answers
  // The driver's error text goes to a fresh file in the system's temporary folder ($TMPDIR, else /tmp).
  std::error_code tmp_ec;
  const fs::path tmp_dir = fs::temp_directory_path(tmp_ec);
  WAAM_THROW_UNLESS(!tmp_ec, "no temporary folder for the Dask driver's errors: " << tmp_ec.message());
  std::string error_template = (tmp_dir / "waam_dask_error_XXXXXX").string();
  const int fd = mkstemp(error_template.data());
  WAAM_THROW_UNLESS(fd >= 0, "cannot create a temporary file in " << tmp_dir.string() << ": " << std::strerror(errno));
  close(fd);
  const char* const error_file = error_template.c_str();

  std::vector<std::string> args = {python, driver.string(), "--scheduler", scheduler, "--waam", options.waam_binary,
                                   "--sweep", sweep.file.string(), "--cwd", fs::current_path().string(),
                                   "--shards", std::to_string(shards), "--threads", "1",
                                   "--out", fs::absolute(shard_root).string()};
  for (const std::string& o : options.overrides) {
    args.push_back("--set");
    args.push_back(o);
  }
  if (options.fresh) args.push_back("--fresh");
  if (options.quiet) args.push_back("--quiet");
  args.insert(args.end(), {"--error-file", error_file});
  const int code = RunAndWait(args);
  std::string reason = ReadFile(error_file);
  fs::remove(error_file);
  if (code == 130) throw Interrupted();
  while (!reason.empty() && (reason.back() == '\n' || reason.back() == '\r')) reason.pop_back();
  if (reason.empty()) reason = "--dask " + scheduler + ": the driver ended with exit code " + std::to_string(code);
  WAAM_THROW_UNLESS(code == 0, reason << "; nothing merged");

  std::vector<fs::path> dirs;
  for (std::size_t k = 0; k < shards; ++k) dirs.push_back(shard_root / ("shard_" + std::to_string(k)));
  return MergeBench(dirs, options.out_dir);
}

}  // namespace waam::analysis
