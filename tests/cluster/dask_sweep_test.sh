#!/usr/bin/env bash
# A local dask.distributed cluster (one dask-scheduler and two dask-worker processes on 127.0.0.1) runs
# tests/cluster/sweep.yaml through `waam sweep --dask`: the merged bench.json equals a local `waam sweep` (timings
# aside). A scheduler address that does not answer is one line, exit 2, nothing merged. Every process it started is
# stopped whatever happens.
# Usage: dask_sweep_test.sh <build dir>
set -euo pipefail
build=$(cd "$1" && pwd)
src=$(cd "$(dirname "$0")/../.." && pwd)
python=/usr/bin/python3
work=$(mktemp -d)
pids=()
fail() { echo "FAIL: $*"; for f in "$work"/*.log; do [ -f "$f" ] && { echo "--- $f"; tail -n 15 "$f"; }; done; exit 1; }
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  rm -rf "$work"
}
trap cleanup EXIT
if ! "$python" -c "import distributed" 2>/dev/null || ! command -v dask-scheduler >/dev/null; then
  echo "SKIP: needs python3-distributed (tools/install_deps.sh)"; exit 77
fi
waam="$build/waam"
cd "$src"   # the sweep's paths as a user gives them, relative to the repository

dask-scheduler --host 127.0.0.1 --port 0 --no-dashboard --scheduler-file "$work/scheduler.json" \
  >"$work/scheduler.log" 2>&1 &
pids+=($!)
disown
for _ in $(seq 150); do [ -s "$work/scheduler.json" ] && break; sleep 0.1; done
[ -s "$work/scheduler.json" ] || fail "dask-scheduler wrote no scheduler file within 15 s"
address=$("$python" -c "import json, sys; print(json.load(open(sys.argv[1]))['address'])" "$work/scheduler.json")
for w in 1 2; do
  dask-worker --scheduler-file "$work/scheduler.json" --nthreads 1 --no-dashboard --host 127.0.0.1 \
    --local-directory "$work/worker$w" >"$work/worker$w.log" 2>&1 &
  pids+=($!)
  disown
done

"$waam" sweep tests/cluster/sweep.yaml -j 2 --threads 1 -q -o "$work/local" >/dev/null || [ $? -eq 3 ] \
  || fail "the local sweep did not run"
code=0
"$waam" sweep tests/cluster/sweep.yaml --dask "$address" -q -o "$work/dask" >"$work/dask.log" 2>&1 || code=$?
[ "$code" = 3 ] || fail "waam sweep --dask exited $code, expected 3 (the planted fault): $(tail -n 3 "$work/dask.log")"
"$python" tests/cluster/bench_json_equal.py "$work/local/bench.json" "$work/dask/bench.json" \
  || fail "the bench from the Dask cluster differs from the local one"
[ -d "$work/dask/dask_shards/shard_5" ] || fail "the shards are not kept for a resume"

# No scheduler at this address (a closed port on the loopback): one line, exit 2, no bench.
code=0
"$waam" sweep tests/cluster/sweep.yaml --dask tcp://127.0.0.1:9 -q -o "$work/nobody" >"$work/nobody.log" 2>&1 \
  || code=$?
[ "$code" = 2 ] || fail "a scheduler that does not answer gave exit $code, expected 2"
grep -q "^waam: error: --dask tcp://127.0.0.1:9: the scheduler does not answer" "$work/nobody.log" \
  || fail "no line saying the scheduler does not answer: $(cat "$work/nobody.log")"
[ "$(wc -l <"$work/nobody.log")" = 1 ] || fail "more than one line for a scheduler that does not answer"
[ ! -e "$work/nobody/bench.json" ] || fail "a bench.json was written although nothing ran"
echo "dask: 6 runs on 2 workers, merged bench equals the local run; a silent scheduler is refused"
