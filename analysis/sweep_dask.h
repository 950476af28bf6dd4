// `waam sweep --dask ADDRESS`: the runs of a sweep as tasks of a dask.distributed cluster, merged into one bench.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "analysis/bench_command.h"
#include "analysis/sweep.h"

namespace waam::analysis {

// Runs every run of `sweep` as one Dask task on the cluster whose scheduler listens at `scheduler` (e.g.
// "tcp://127.0.0.1:8786"), through the driver analysis/data/dask/dask_sweep.py started with /usr/bin/python3
// ($WAAM_PYTHON overrides it): each task runs `waam sweep --shard K/N --threads 1` (one run) on a worker, whose
// task slots (`dask-worker --nthreads`) set how many run at once, and sends its folder back; the
// shards are kept under <out_dir>/dask_shards (a rerun resumes from them) and merged into options.out_dir as
// `waam bench --merge` does. Returns the merged bench.json. Throws InputError naming the address when the scheduler
// does not answer or a shard could not run on its worker (nothing is merged then).
nlohmann::json RunSweepOnDask(const Sweep& sweep, const BenchOptions& options, const std::string& scheduler);

}  // namespace waam::analysis
