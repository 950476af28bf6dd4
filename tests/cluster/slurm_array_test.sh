#!/usr/bin/env bash
# A real single-node Slurm runs docs/cluster/bench_array.sh as a 3-task array over tests/cluster/sweep.yaml and a
# dependent merge job, as docs/CLUSTER.md tells users to. Checks: the merged bench.json equals one local run of the
# sweep (timings aside); task 1, cancelled in the middle of its second run and requeued, resumes and reuses its
# finished run; the planted fault (exit 3) fails no task and the merge reports it; each task's CPUs and memory reach
# waam as --threads and --mem-gb. The cluster is brought down whatever happens.
# Usage: slurm_array_test.sh <build dir>
set -euo pipefail
if [ "$(id -u)" != 0 ] || ! [ -x /usr/sbin/slurmctld ] || ! command -v sbatch >/dev/null; then
  echo "SKIP: needs root and Slurm (tools/install_deps.sh installs slurmctld, slurmd, slurm-client, munge)"; exit 77
fi
build=$(cd "$1" && pwd)
src=$(cd "$(dirname "$0")/../.." && pwd)
python=/usr/bin/python3
work=$(mktemp -d)
cluster="$work/cluster"
# On failure: the tasks' logs and the daemons' last lines (why a task failed before it printed anything).
fail() {
  echo "FAIL: $*"
  for f in "$work"/logs/* "$cluster"/log/slurmctld.log "$cluster"/log/slurmd.log; do
    [ -f "$f" ] && { echo "--- $f"; tail -n 20 "$f"; }
  done
  exit 1
}
cleanup() { bash "$src/tools/slurm_local.sh" down "$cluster" || true; rm -rf "$work"; }
trap cleanup EXIT
# Different ports from a developer's own test cluster; the Release and sanitizer suites run one after the other.
export WAAM_SLURMCTLD_PORT=${WAAM_SLURMCTLD_PORT:-16917} WAAM_SLURMD_PORT=${WAAM_SLURMD_PORT:-16918}
bash "$src/tools/slurm_local.sh" up "$cluster"
source "$cluster/env"
export PATH="$build:$PATH"   # the tasks find this build's waam (sbatch exports the environment)
mkdir -p "$work/logs"

# A bounded wait until `squeue` lists none of the jobs given (they ended), at most $1 seconds.
wait_jobs() {
  local limit=$1; shift
  local deadline=$(( $(date +%s) + limit ))
  while [ -n "$(squeue -h -j "$(IFS=,; echo "$*")" 2>/dev/null)" ]; do
    [ "$(date +%s)" -lt "$deadline" ] || fail "jobs $* still in the queue after $limit s: $(squeue -h -j "$(IFS=,; echo "$*")")"
    sleep 0.2
  done
}
# The state and exit code of a job (or array task) as slurmctld still remembers it (MinJobAge).
job_field() { scontrol show job "$1" | tr ' ' '\n' | sed -n "s/^$2=//p" | head -n 1; }

waam sweep "$src/tests/cluster/sweep.yaml" -j 1 --threads 1 -q -o "$work/local" || [ $? -eq 3 ] \
  || fail "the local sweep did not run"

out="$work/array"
jid=$(sbatch --parsable --array=0-2 --cpus-per-task=1 --mem=1500M -o "$work/logs/task_%a.out" \
  "$src/docs/cluster/bench_array.sh" "$src/tests/cluster/sweep.yaml" "$out") || fail "sbatch refused the array"

# Cancel task 1 once its first run is finished and its second (the larger block) is under way, then requeue it.
deadline=$(( $(date +%s) + 120 ))
until [ "$(find "$out/shard_1" -name bench_entry.json 2>/dev/null | wc -l)" -ge 1 ]; do
  [ "$(date +%s)" -lt "$deadline" ] || fail "task 1 finished no run within 120 s"
  sleep 0.05
done
scancel "${jid}_1"
deadline=$(( $(date +%s) + 30 ))
until [ "$(job_field "${jid}_1" JobState)" = CANCELLED ]; do
  [ "$(date +%s)" -lt "$deadline" ] || fail "task 1 not cancelled: $(job_field "${jid}_1" JobState)"
  sleep 0.1
done
[ ! -f "$out/shard_1/bench.json" ] || fail "task 1 had finished its shard before it was cancelled: nothing to resume"
scontrol requeue "${jid}_1" || fail "scontrol requeue ${jid}_1 refused"
# Slurm holds a requeued job for two minutes (its begin time); a user in a hurry releases it the same way.
scontrol update JobId="${jid}_1" StartTime=now || fail "could not release the requeued task"
wait_jobs 240 "$jid"

for task in 0 1 2; do
  state=$(job_field "${jid}_$task" JobState) code=$(job_field "${jid}_$task" ExitCode)
  [ "$state" = COMPLETED ] && [ "$code" = 0:0 ] || fail "task $task ended $state with exit code $code"
done
mid=$(sbatch --parsable --dependency=afterany:"$jid" -o "$work/logs/merge.out" \
  --wrap "waam bench --merge $out/shard_0 $out/shard_1 $out/shard_2 -q -o $out/merged") || fail "sbatch refused the merge"
wait_jobs 120 "$mid"
[ -s "$out/merged/bench.json" ] || fail "the merge job wrote no bench.json ($(job_field "$mid" JobState))"

"$python" "$src/tests/cluster/bench_json_equal.py" "$work/local/bench.json" "$out/merged/bench.json" \
  || fail "the merged bench differs from a local run"
"$python" - "$out" <<'PY' || fail "shard checks"
import json, sys
out = sys.argv[1]
merged = json.load(open(f"{out}/merged/bench.json"))
assert merged["counts"] == {"pass": 5, "expected_fail": 0, "fail": 1, "total": 6}, merged["counts"]
failed = [s["id"] for s in merged["scenarios"] if s["outcome"] == "fail"]
assert len(failed) == 1 and merged["scenarios"][5]["exit_code"] == 3, failed
resumed = json.load(open(f"{out}/shard_1/bench.json"))["timing"]
assert resumed["reused_results"] == 1, f"the requeued task reused {resumed['reused_results']} runs, expected 1"
for k in range(3):
    timing = json.load(open(f"{out}/shard_{k}/bench.json"))["timing"]
    # --cpus-per-task=1 --mem=1500M: one thread, 80 % of 1500 MB.
    assert timing["jobs"] * timing["threads_per_job"] == 1, timing
    assert abs(timing["memory_budget_mb"] - 1200) < 1, timing["memory_budget_mb"]
PY
grep -q "did not end as expected" "$work/logs/task_2.out" || fail "task 2 did not report its planted fault"
echo "slurm array: 3 tasks, a requeued task resumed, merged bench equals the local run"
